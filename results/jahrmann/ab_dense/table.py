"""The table of README.md, from the rounds' frames.csv (python3, standard library only).

    python3 results/jahrmann/ab_dense/table.py
"""
import csv
import pathlib
import statistics as st

HERE = pathlib.Path(__file__).parent
SCENES = ["prairie_flyover", "football_field", "meadow"]
COLUMNS = ["gpu_wall_ms", "gpu_ts_render_ms", "gpu_ts_background_ms"]


def medians(build, scene):
    """Each round's median of each column, and of the wall's rest (compute, submission)."""
    out = {c: [] for c in COLUMNS + ["rest"]}
    for rnd in sorted(HERE.glob(f"{build}-*")):
        frames = list(csv.DictReader(open(rnd / scene / "frames.csv")))
        m = {c: st.median(float(f[c]) for f in frames) for c in COLUMNS}
        m["rest"] = m["gpu_wall_ms"] - m["gpu_ts_render_ms"] - m["gpu_ts_background_ms"]
        for c, v in m.items():
            out[c].append(v)
    return out


print("| scene | build | GPU wall | render pass | background | rest (compute, submission) |")
print("|---|---|---|---|---|---|")
for scene in SCENES:
    for build in ["old", "new"]:
        m = medians(build, scene)
        cells = [f"{st.median(v):.1f} ({min(v):.1f}-{max(v):.1f})" for v in
                 (m["gpu_wall_ms"], m["gpu_ts_render_ms"], m["gpu_ts_background_ms"], m["rest"])]
        print(f"| {scene} | {build} | " + " | ".join(cells) + " |")
    old, new = medians("old", scene)["gpu_wall_ms"], medians("new", scene)["gpu_wall_ms"]
    pairs = [n / o for o, n in zip(old, new)]
    print(f"| {scene} | new / old, round by round | {min(pairs):.2f}-{max(pairs):.2f} (median {st.median(pairs):.2f}) | | | |")
