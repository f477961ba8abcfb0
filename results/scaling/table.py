#!/usr/bin/env python3
"""The scaling README's tables from runs.csv: median GPU wall (or frame) ms per frame, the mean of
the repetitions' medians, per technique and terrain size, and the growth from 80 m to 400 m
overall (means) and between any two repetitions (a 400 m one over an 80 m one).

    python3 results/scaling/table.py [results/scaling] [gpu|frame]
"""
import csv
import re
import sys
from collections import defaultdict

folder = sys.argv[1] if len(sys.argv) > 1 else "results/scaling"
clock = sys.argv[2] if len(sys.argv) > 2 else "gpu"
column = {"gpu": "gpu_wall_ms_median", "frame": "frame_ms_median"}[clock]
ORDER = ["reference", "zhang", "boulanger", "bakay", "perbet", "jahrmann"]

times = defaultdict(lambda: defaultdict(dict))  # technique -> size -> repetition -> ms
triangles = defaultdict(dict)
for r in csv.DictReader(open(f"{folder}/runs.csv")):
    if r["status"] != "ok":
        continue
    size = int(re.search(r"size=\[(\d+)", r["scene_variant"]).group(1))
    times[r["technique"]][size][int(r["repetition"])] = float(r[column])
    triangles[r["technique"]][size] = int(r["triangles"])

sizes = sorted({s for t in times.values() for s in t})
head = " | ".join(f"{s} m" for s in sizes)
print(f"| technique | {head} | 400 / 80 | by repetition |" + (" triangles |" if clock == "gpu" else ""))
print("|---" * (len(sizes) + 3 + (clock == "gpu")) + "|")
for t in ORDER:
    if t not in times:
        continue
    mean = {s: sum(v.values()) / len(v) for s, v in times[t].items()}
    # Every repetition at 400 m over every one at 80 m.
    by_rep = [a / b for a in times[t][400].values() for b in times[t][80].values()]
    growth = mean[400] / mean[80]
    bold = "**" if t != "reference" else ""
    cells = " | ".join(f"{mean[s]:.0f}" for s in sizes)
    row = f"| {t} | {cells} | {bold}{growth:.2f}{bold} | {min(by_rep):.2f}-{max(by_rep):.2f} |"
    if clock == "gpu":
        row += f" {triangles[t][80] / 1e3:,.0f} k → {triangles[t][400] / 1e3:,.0f} k |".replace(",", " ")
    print(row)
