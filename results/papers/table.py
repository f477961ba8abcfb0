#!/usr/bin/env python3
"""Tables of results/papers/README.md and the departures tables of the technique READMEs, from
the sweeps' runs.csv (python3, standard library only):

    python3 results/papers/table.py papers              # results/papers/runs.csv
    python3 results/papers/table.py departures zhang    # results/departures_zhang/runs.csv
    python3 results/papers/table.py winds               # results/winds/runs.csv
"""
import csv
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HOME = {  # each paper's own scene in experiments/papers.toml
    "zhang": "meadow_fluid",
    "perbet": "meadow_primitives",
    "bakay": "meadow_point_source",
    "boulanger": "boulanger_football_field_human",
}


def rows(folder):
    with open(ROOT / "results" / folder / "runs.csv", newline="") as f:
        return list(csv.DictReader(f))


def params(r):
    return dict(kv.split("=", 1) for kv in r["params"].split(";") if "=" in kv)


def num(r, k):
    return float(r[k]) if r[k] else None


def fmt(v, d=1):
    return "" if v is None else f"{v:.{d}f}"


def papers():
    rs = rows("papers")
    scenes = list(dict.fromkeys(r["scene"] for r in rs))
    print("| scene | technique | operating point | GPU ms (p5–p95) | x reference | FLIP vs reference | at 1/4 | blades drawn | represented | other cores busy |")
    print("|---|---|---|---|---:|---:|---:|---:|---:|---:|")
    for s in scenes:
        for r in rs:
            if r["scene"] != s:
                continue
            p = params(r).get("variant", "default")
            home = " (home)" if HOME.get(r["technique"]) == s else ""
            print(
                f"| {s} | {r['technique']}{home} | {p} | {fmt(num(r, 'gpu_wall_ms_median'))} "
                f"({fmt(num(r, 'gpu_wall_ms_p5'))}–{fmt(num(r, 'gpu_wall_ms_p95'))}) "
                f"| {fmt(num(r, 'gpu_wall_ratio_to_reference'), 3)} | {fmt(num(r, 'flip_vs_reference'), 3)} "
                f"| {fmt(num(r, 'flip_vs_reference_quarter'), 3)} | {r['blades_drawn']} | {r['blades_represented']} "
                f"| {fmt(num(r, 'host_other_cores'), 2)} |"
            )


def changes(rs, r):
    """Keys a `paper` row sets beyond the plain paper row's (the departure it measures): the
    values fewer than half of the paper rows share."""
    p = params(r)
    if p.get("variant") != "paper":
        return []
    papers_ = [params(x) for x in rs if params(x).get("variant") == "paper"]
    return [f"{k}={v}" for k, v in p.items() if 2 * sum(q.get(k) == v for q in papers_) < len(papers_)]


def departures(technique):
    rs = [r for r in rows(f"departures_{technique}") if r["technique"] == technique]
    paper = next(r for r in rs if params(r).get("variant") == "paper" and not changes(rs, r))
    base_ms, base_flip = num(paper, "gpu_wall_ms_median"), num(paper, "flip_vs_reference")
    print("| configuration | GPU ms (p5–p95) | x the paper's time | CPU update ms | FLIP vs reference | change against the paper's FLIP | other cores busy |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for r in rs:
        c = changes(rs, r)
        name = params(r).get("variant", "default") if not c else "paper + " + ", ".join(c)
        ms, fl = num(r, "gpu_wall_ms_median"), num(r, "flip_vs_reference")
        print(
            f"| {name} | {fmt(ms)} ({fmt(num(r, 'gpu_wall_ms_p5'))}–{fmt(num(r, 'gpu_wall_ms_p95'))}) "
            f"| {fmt(ms / base_ms, 2)} | {fmt(num(r, 'update_ms_median'), 1)} | {fmt(fl, 4)} | {fl - base_flip:+.4f} | {fmt(num(r, 'host_other_cores'), 2)} |"
        )


def winds():
    rs = rows("winds")
    scenes = list(dict.fromkeys(r["scene"] for r in rs))
    techniques = list(dict.fromkeys(r["technique"] for r in rs))
    cell = {(r["scene"], r["technique"]): r for r in rs}
    print("GPU ms (x reference) and FLIP against the reference in the same wind:\n")
    print("| technique | " + " | ".join(scenes) + " |")
    print("|---|" + "---|" * len(scenes))
    for t in techniques:
        cells = []
        for s in scenes:
            r = cell.get((s, t))
            if r is None or r["status"] != "ok":
                cells.append(r["error"][:40] if r else "")
                continue
            ms = num(r, "gpu_wall_ms_median")
            ratio = num(r, "gpu_wall_ratio_to_reference")
            flip = num(r, "flip_vs_reference")
            extra = "" if t == "reference" else f" ({fmt(ratio, 3)}x), FLIP {fmt(flip, 3)}"
            cells.append(f"{fmt(ms)}{extra}")
        print(f"| {t} | " + " | ".join(cells) + " |")
    busy = [num(r, "host_other_cores") for r in rs if r["host_other_cores"]]
    print(f"\nOther cores busy while measuring: {min(busy):.2f}-{max(busy):.2f} (of 2).")


if __name__ == "__main__":
    if sys.argv[1:2] == ["papers"]:
        papers()
    elif sys.argv[1:2] == ["winds"]:
        winds()
    elif sys.argv[1:2] == ["departures"] and len(sys.argv) == 3:
        departures(sys.argv[2])
    else:
        sys.exit(__doc__)
