#!/usr/bin/env python3
"""Prints the Table 2 comparison (Markdown) from the runs.csv files make.sh wrote."""
import csv
import pathlib

HERE = pathlib.Path(__file__).parent
# Bakay et al. 2002, Table 2: frames per second on a GeForce3 (polygons 512 per shell).
PAPER = {1: (293.5, 130.8), 9: (47.0, 22.8), 17: (25.6, 12.4), 33: (13.4, 6.5), 65: (6.9, 3.3)}
SIZES = ["640x480", "1024x768"]


def cpu_seconds(folder):
    user, system, _wall = (float(x) for x in (HERE / folder / "cpu_time.txt").read_text().split())
    return user + system


def summary(folder):
    with open(HERE / folder / "meadow" / "runs.csv") as f:
        return next(csv.DictReader(f))


print("| shells | size | paper fps | paper ms | GPU wall ms (p5–p95) | frame ms | x paper ms | x reference | process CPU s |")
print("|---:|---|---:|---:|---|---:|---:|---:|---:|")
for size_index, size in enumerate(SIZES):
    ref = float(summary(f"reference_{size}")["gpu_wall_ms_median"])
    for shells, fps in PAPER.items():
        r = summary(f"shells{shells}_{size}")
        wall, p5, p95 = (float(r[k]) for k in ("gpu_wall_ms_median", "gpu_wall_ms_p5", "gpu_wall_ms_p95"))
        paper_ms = 1000.0 / fps[size_index]
        print(
            f"| {shells} | {size} | {fps[size_index]} | {paper_ms:.1f} | {wall:.1f} ({p5:.1f}–{p95:.1f}) "
            f"| {float(r['frame_ms_median']):.1f} | {wall / paper_ms:.1f} | {wall / ref:.2f} "
            f"| {cpu_seconds(f'shells{shells}_{size}'):.1f} |"
        )
    r = summary(f"reference_{size}")
    print(
        f"| reference | {size} | | | {ref:.1f} ({float(r['gpu_wall_ms_p5']):.1f}–{float(r['gpu_wall_ms_p95']):.1f}) "
        f"| {float(r['frame_ms_median']):.1f} | | 1.00 | {cpu_seconds(f'reference_{size}'):.1f} |"
    )
