#!/usr/bin/env python3
"""The shells probe's table (README.md), from its runs.csv: means of the repetitions per shell
count, and what each step of shells added, measured against modelled. Usage, from the
repository root:

    python3 results/cost_model/bakay_shells_probe/table.py
"""
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from tables import ROOT, num, params, runs  # noqa: E402  (results/tables.py: the shared helpers)


def main():
    by = {}
    for r in runs(Path(__file__).resolve().parent.relative_to(ROOT)):
        by.setdefault(int(params(r)["shells"]), []).append(r)
    print("| shells | counted fragments | GPU wall ms | model ms | measured / model "
          "| the step from the row above: measured / model ms | its ratio "
          "| beyond the model, ns an added fragment |")
    print("|---:|---:|---:|---:|---:|---|---:|---:|")
    before = None
    for shells in sorted(by):
        rows = by[shells]
        measured = statistics.mean(num(r, "gpu_wall_ms_median") for r in rows)
        model = statistics.mean(num(r, "model_ms") for r in rows)
        fragments = num(rows[0], "fragment_invocations")
        step = " |  | "
        if before:
            dm, dp, df = measured - before[0], model - before[1], fragments - before[2]
            step = f"{dm:.1f} / {dp:.1f} | {dm / dp:.2f} | {(dm - dp) / df * 1e6:.1f}"
        print(f"| {shells} | {fragments:,.0f} | {measured:.1f} | {model:.1f} "
              f"| {measured / model:.2f} | {step} |")
        before = (measured, model, fragments)


if __name__ == "__main__":
    main()
