#!/usr/bin/env python3
"""The levels probe's table (README.md), from the kept runs.csv files. Usage, from the
repository root:

    python3 results/jahrmann/levels_probe/table.py
"""
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from tables import params  # noqa: E402  (results/tables.py: the shared helpers)

HERE = os.path.dirname(os.path.abspath(__file__))
# The meadow's blades at each density (`../README.md`'s density table).
POPULATION = {"103.75": "500 312", "207.5": "1 000 098", "830": "4 002 240"}


def main():
    print("| probe | scene blades | far_keep | far_widen | GPU wall ms | model ms | measured / model | "
          "fragments counted | samples kept | model: opaque fragments ms |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    runs = []
    for name in ["keep_widen", "density_widen"]:
        for r in csv.DictReader(open(os.path.join(HERE, f"{name}.runs.csv"))):
            runs.append((name, r))
            print(f"| {name} | {POPULATION[r['scene_variant'].split('grass.density=')[1].split(';')[0]]} "
                  f"| {params(r)['far_keep']} | {params(r)['far_widen']} "
                  f"| {float(r['gpu_wall_ms_median']):.0f} | {float(r['model_ms']):.0f} "
                  f"| {float(r['model_ratio']):.2f} | {int(r['fragment_invocations']) / 1e6:.1f} M "
                  f"| {int(r['fragments_passed']) / 1e6:.2f} M | {float(r['model_fragment_opaque_ms']):.0f} |")
    print()
    print("| probe | scene blades | far_keep | fragments the widening adds | samples kept it adds | "
          "measured Δ ms | model Δ ms |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in ["keep_widen", "density_widen"]:
        group = [r for n, r in runs if n == name]
        for r in group:
            if params(r)["far_widen"] != "4":
                continue
            twin = next(o for o in group if params(o)["far_widen"] == "1"
                        and params(o)["far_keep"] == params(r)["far_keep"]
                        and o["scene_variant"] == r["scene_variant"])
            d = lambda k: float(r[k]) - float(twin[k])
            print(f"| {name} | {POPULATION[r['scene_variant'].split('grass.density=')[1].split(';')[0]]} "
                  f"| {params(r)['far_keep']} | {d('fragment_invocations') / 1e6:+.1f} M "
                  f"| {d('fragments_passed') / 1e6:+.2f} M | {d('gpu_wall_ms_median'):+.0f} "
                  f"| {d('model_ms'):+.0f} |")


if __name__ == "__main__":
    main()
