"""The tables of README.md, from the rounds' CSV files (python3, standard library only).

    python3 results/jahrmann/ab_dense/table.py
"""
import csv
import pathlib
import statistics as st

HERE = pathlib.Path(__file__).parent
SCENES = ["prairie_flyover", "football_field", "meadow"]
COLUMNS = ["gpu_wall_ms", "gpu_ts_render_ms", "gpu_ts_background_ms"]


def cell(values):
    """The median of the rounds and their range."""
    return f"{st.median(values):.1f} ({min(values):.1f}-{max(values):.1f})"


def pairs(old, new):
    """Round by round, new over old: range and median."""
    p = [n / o for o, n in zip(old, new)]
    return f"{min(p):.2f}-{max(p):.2f} (median {st.median(p):.2f})"


def run_rounds(size, build, scene):
    """Each `run` round's median of each column, and of the wall's rest (compute, submission)."""
    out = {c: [] for c in COLUMNS + ["rest"]}
    for rnd in sorted((HERE / size).glob(f"{build}-*")):
        frames = list(csv.DictReader(open(rnd / scene / "frames.csv")))
        m = {c: st.median(float(f[c]) for f in frames) for c in COLUMNS}
        m["rest"] = m["gpu_wall_ms"] - m["gpu_ts_render_ms"] - m["gpu_ts_background_ms"]
        for c, v in m.items():
            out[c].append(v)
    return out


def sweep_rounds(build, scene, width):
    """Each sweep round's median GPU wall time of one configuration."""
    out = []
    for rnd in sorted((HERE / "sweeps").glob(f"{build}-*")):
        for row in csv.DictReader(open(rnd / "runs.csv")):
            if row["scene"] == scene and row["width"] == width:
                out.append(float(row["gpu_wall_ms_median"]))
    return out


for size in ["320x180", "640x360"]:
    print(f"\n`{size}/` (ms, the median of the rounds' medians and their range):\n")
    print("| scene | build | GPU wall | render pass | background | rest (compute, submission) |")
    print("|---|---|---|---|---|---|")
    for scene in SCENES:
        rounds = {b: run_rounds(size, b, scene) for b in ["old", "new"]}
        for build, m in rounds.items():
            cells = [cell(m[c]) for c in ["gpu_wall_ms", "gpu_ts_render_ms", "gpu_ts_background_ms", "rest"]]
            print(f"| {scene} | {build} | " + " | ".join(cells) + " |")
        walls = [rounds[b]["gpu_wall_ms"] for b in ["old", "new"]]
        print(f"| {scene} | new / old, round by round | {pairs(*walls)} | | | |")

print("\n`sweeps/` (GPU wall ms, the median of the rounds and their range):\n")
print("| scene | size | old | new | new / old, round by round |")
print("|---|---|---|---|---|")
for scene in SCENES:
    for width, size in [("320", "320x180"), ("640", "640x360")]:
        old, new = sweep_rounds("old", scene, width), sweep_rounds("new", scene, width)
        print(f"| {scene} | {size} | {cell(old)} | {cell(new)} | {pairs(old, new)} |")
