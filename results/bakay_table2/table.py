#!/usr/bin/env python3
"""The table of results/bakay_table2/README.md from its runs.csv (python3, standard library):

    python3 results/bakay_table2/table.py
"""
import csv
import statistics
from pathlib import Path

HERE = Path(__file__).resolve().parent
# Bakay et al. 2002, Table 2: shells -> (polygons, fps at 640x480, fps at 1024x768).
PAPER = {1: (512, 293.5, 130.8), 9: (4608, 47.0, 22.8), 17: (8704, 25.6, 12.4),
         33: (16896, 13.4, 6.5), 65: (33280, 6.9, 3.3)}
SIZES = ["640x480", "1024x768"]


def params(r):
    return dict(kv.split("=", 1) for kv in r["params"].split(";") if "=" in kv)


with open(HERE / "runs.csv", newline="") as f:
    rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
cells = {}
for r in rows:
    size = f"{r['width']}x{r['height']}"
    key = (size, "reference" if r["technique"] == "reference" else int(params(r)["shells"]))
    cells.setdefault(key, []).append(r)


def med(rs, k):
    return statistics.median(float(r[k]) for r in rs if r[k])


def span(rs, k):
    v = [float(r[k]) for r in rs if r[k]]
    return min(v), max(v)


print("| shells | size | paper polygons | our triangles (per shell) | paper fps | paper ms | GPU wall ms, median of 3 (range of the repetitions) | x paper ms | x reference | FLIP vs reference | other cores busy |")
print("|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|")
for size in SIZES:
    for shells, (polys, fps640, fps1024) in PAPER.items():
        rs = cells[(size, shells)]
        fps = fps640 if size == "640x480" else fps1024
        ms = med(rs, "gpu_wall_ms_median")
        lo, hi = span(rs, "gpu_wall_ms_median")
        tri = med(rs, "triangles")
        busy = span(rs, "host_other_cores")
        print(f"| {shells} | {size} | {polys} | {tri:.0f} ({tri / shells:.0f}) | {fps} | {1000 / fps:.1f} "
              f"| {ms:.1f} ({lo:.1f}–{hi:.1f}) | {ms / (1000 / fps):.1f} | {med(rs, 'gpu_wall_ratio_to_reference'):.2f} "
              f"| {med(rs, 'flip_vs_reference'):.3f} | {busy[0]:.2f}–{busy[1]:.2f} |")
    rs = cells[(size, "reference")]
    lo, hi = span(rs, "gpu_wall_ms_median")
    print(f"| reference | {size} | | {med(rs, 'triangles'):.0f} | | | {med(rs, 'gpu_wall_ms_median'):.1f} ({lo:.1f}–{hi:.1f}) | | 1.00 | | |")
