#!/usr/bin/env python3
"""The lookup probe's table (README.md): each sweep's GPU wall time, model and terms, and the
differences between the builds, from the kept runs.csv files. Usage, from the repository root:

    python3 results/bakay_table2/lookup_probe/table.py
"""
import csv
import glob
import os
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from tables import num, params  # noqa: E402  (results/tables.py: the shared helpers)

HERE = os.path.dirname(os.path.abspath(__file__))
BUILDS = ["shipped", "level", "nearest"]


def rows():
    out = {}
    for build in BUILDS:
        for path in sorted(glob.glob(os.path.join(HERE, f"{build}_*.runs.csv"))):
            sweep = os.path.basename(path).split(".")[0]
            for r in csv.DictReader(open(path)):
                shells = int(params(r)["shells"])
                out.setdefault((build, shells), []).append((sweep, r))
    return out


def f(r, k):
    return num(r, k) or 0.0


def main():
    data = rows()
    print("| sweep | shells | GPU wall ms | model ms | measured / model | mip blends | "
          "model: blends ms | model: fragment transcendentals + arithmetic ms |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for (build, shells), runs in sorted(data.items(), key=lambda kv: (kv[0][1], BUILDS.index(kv[0][0]))):
        for sweep, r in runs:
            print(f"| {sweep} | {shells} | {f(r, 'gpu_wall_ms_median'):.1f} | {f(r, 'model_ms'):.1f} | "
                  f"{f(r, 'model_ratio'):.3f} | {int(f(r, 'texture_mip_blends')):,} | "
                  f"{f(r, 'model_texture_mip_blend_ms'):.1f} | "
                  f"{f(r, 'model_fragment_transcendental_ms') + f(r, 'model_fragment_arithmetic_ms'):.1f} |")
    print()
    mean = lambda build, shells, key: statistics.mean(f(r, key) for _, r in data[(build, shells)])
    print("| shells | change | measured Δ ms | model Δ ms | per lookup, measured / model ns |")
    print("|---:|---|---:|---:|---:|")
    for shells in sorted({s for _, s in data}):
        for a, b, what in [("shipped", "level", "`textureSampleGrad` → `textureSampleLevel` at the level the shader works out"),
                           ("level", "nearest", "a lane's level blended with the next → the nearest level alone")]:
            dm = mean(b, shells, "gpu_wall_ms_median") - mean(a, shells, "gpu_wall_ms_median")
            dp = mean(b, shells, "model_ms") - mean(a, shells, "model_ms")
            lookups = mean(a, shells, "texture_explicit_levels")
            print(f"| {shells} | {what} | {dm:+.1f} | {dp:+.1f} | {dm / lookups * 1e6:+.2f} / {dp / lookups * 1e6:+.2f} |")


if __name__ == "__main__":
    main()
