#!/usr/bin/env python3
"""The tables of the results READMEs that `results/papers/table.py` does not make, and the
comparison a re-made folder's README starts from (python3, standard library only):

    python3 results/tables.py diff results/winds                 # against the committed version
    python3 results/tables.py diff results/winds --rev 7c74de8   # against another revision's
    python3 results/tables.py model results/cost_model/epyc_zen4 \\
        results/cost_model/epyc_zen4/again results/cost_model/epyc_zen4/third
    python3 results/tables.py msaa results/cost_model/coverage/sweep
    python3 results/tables.py jahrmann results/jahrmann/density
    python3 results/tables.py zhang_target results/zhang_target

`diff` pairs each run of a folder's `runs.csv` with the run of the same configuration in the
version of that file committed at a revision, and prints what a re-make has to say: the counts
that changed (anything else is timing), each run's GPU time against the old one and its
measured / model ratio then and now, and whether the pictures in `images/` are byte for byte
the same, and where they are not, how far they differ (share of pixels, largest step of a
channel: another CPU's rounding moves a few pixels by a level or two, a change of what is drawn
moves many). Run it from the repository root.
"""
import csv
import io
import statistics
import struct
import subprocess
import sys
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# The work columns of runs.csv: what a technique did, not how long it took. FLIP is here too:
# the same pictures give the same FLIP.
COUNTS = [
    "blades_drawn", "blades_represented", "triangles", "draw_calls", "instances", "gpu_bytes", "primitive_inputs",
    "vertex_invocations", "clipper_primitives_out", "fragment_invocations",
    "compute_invocations", "fragments_opaque", "fragments_alpha_tested", "fragments_blended",
    "fragments_passed", "upload_bytes", "background_fragment_invocations", "texture_loads",
    "float_texture_loads", "vertex_texture_loads", "vertex_float_texture_loads",
    "texture_samples", "float_texture_samples", "texture_mip_blends", "texture_explicit_levels", "head_primitives", "vertex_transcendentals",
    "fragment_transcendentals", "compute_transcendentals", "vertex_arithmetic",
    "fragment_arithmetic", "compute_arithmetic", "compute_barriers", "compute_storage",
    "vertex_storage", "compute_divisions", "flip_vs_reference", "flip_vs_reference_quarter",
]
SCENES = ["meadow", "football_field", "prairie_flyover"]
WITHIN = (0.75, 1.25)  # issue 20's band for measured / model


def git(*args):
    out = subprocess.run(["git", *args], capture_output=True, cwd=ROOT)
    if out.returncode != 0:
        sys.exit(f"git {' '.join(args)}: {out.stderr.decode().strip()}")
    return out.stdout


def runs(folder, rev=None):
    """The rows of `folder/runs.csv`, from the working tree or as committed at `rev`."""
    path = Path(folder) / "runs.csv"
    if rev is None:
        with open(ROOT / path, newline="") as f:
            return list(csv.DictReader(f))
    text = git("show", f"{rev}:{path.as_posix()}").decode()
    return list(csv.DictReader(io.StringIO(text)))


def num(row, key):
    value = row.get(key, "")
    return float(value) if value not in ("", None) else None


def params(row):
    return dict(kv.split("=", 1) for kv in row["params"].split(";") if "=" in kv)


def config(row):
    """What makes two rows the same run: everything but the clock."""
    return (row["technique"], row["scene"], row.get("scene_variant", ""), row["width"],
            row["height"], row.get("msaa", ""), row["params"], row.get("repetition", ""))


def within(ratio):
    return ratio is not None and WITHIN[0] <= ratio <= WITHIN[1]


def span(values, digits=2):
    values = [v for v in values if v is not None]
    return f"{min(values):.{digits}f}-{max(values):.{digits}f}" if values else "–"


def diff(folder, rev="HEAD"):
    new, old = runs(folder), runs(folder, rev)
    by_config = {config(r): r for r in old}
    times, frames = [], []
    print(f"{folder}: {len(new)} runs against {rev}'s {len(old)}\n")
    print("| run | GPU ms then | now | now / then | measured / model then | now | counts that changed |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for row in new:
        name = f"{row['technique']} {row['scene']} {row['width']}x{row['height']}"
        extra = [row.get("scene_variant", ""), "msaa" if row.get("msaa") == "true" else "",
                 "paper" if "variant=paper" in row["params"] else "", f"r{row.get('repetition', 0)}"]
        name = " ".join([name] + [e for e in extra if e])
        then = by_config.get(config(row))
        if then is None:
            print(f"| {name} | | | | | | a configuration {rev} did not run |")
            continue
        changed = [f"{c} {then[c]} → {row[c]}" for c in COUNTS
                   if c in row and c in then and row[c] != then[c]]
        g0, g1 = num(then, "gpu_wall_ms_median"), num(row, "gpu_wall_ms_median")
        f0, f1 = num(then, "frame_ms_median"), num(row, "frame_ms_median")
        times.append(g1 / g0)
        frames.append(f1 / f0)
        m0, m1 = num(then, "model_ratio"), num(row, "model_ratio")
        fmt = lambda v: "" if v is None else f"{v:.2f}"
        print(f"| {name} | {g0:.2f} | {g1:.2f} | {g1 / g0:.2f} | {fmt(m0)} | {fmt(m1)} | "
              f"{'; '.join(changed)} |")
    print()
    if times:
        print(f"GPU time now / then: median {statistics.median(times):.3f}, {span(times)}; "
              f"frame time {statistics.median(frames):.3f}, {span(frames)}")
    for label, rows in ((rev, old), ("now", new)):
        ratios = [num(r, "model_ratio") for r in rows]
        ratios = [r for r in ratios if r is not None]
        if ratios:
            print(f"measured / model {label}: {sum(map(within, ratios))} of {len(ratios)} within "
                  f"±25 %, {span(ratios)}")
    images = ROOT / folder / "images"
    if images.is_dir():
        changed = git("diff", "--name-only", rev, "--", str(Path(folder) / "images")).decode().split()
        total = len(list(images.glob("*.png")))
        print(f"images: {total - len(changed)} of {total} byte for byte {rev}'s")
        steps = [pixel_difference(git("show", f"{rev}:{name}"), (ROOT / name).read_bytes())
                 for name in changed if (ROOT / name).exists()]
        steps = [s for s in steps if s is not None]
        if steps:
            shares = [100 * s[0] for s in steps]
            print(f"  the other {len(steps)}: {min(shares):.1f}-{max(shares):.1f} % of their pixels "
                  f"differ, by at most {max(s[1] for s in steps)} of 255 in a channel")


def png_pixels(data):
    """(width, height, bytes per pixel, pixel bytes) of an 8-bit RGB or RGBA PNG (what the
    harness writes), or None for any other kind."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    pos, idat, header = 8, b"", None
    while pos + 8 <= len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    if header is None or header[2] != 8 or header[3] not in (2, 6) or header[6] != 0:
        return None
    width, height, bpp = header[0], header[1], 3 if header[3] == 2 else 4
    raw, stride = zlib.decompress(idat), width * bpp
    out, prev, at = bytearray(), bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += line
        prev = line
    return width, height, bpp, bytes(out)


def pixel_difference(old_png, new_png):
    """(share of pixels that differ, largest difference of a channel in 255ths) between two
    PNGs of one size, or None where either is not an 8-bit RGB(A) PNG or the sizes differ."""
    old, new = png_pixels(old_png), png_pixels(new_png)
    if old is None or new is None or old[:3] != new[:3]:
        return None
    bpp, a, b = old[2], old[3], new[3]
    differing, largest = 0, 0
    for at in range(0, len(a), bpp):
        step = max(abs(x - y) for x, y in zip(a[at:at + bpp], b[at:at + bpp]))
        differing += step > 0
        largest = max(largest, step)
    return differing / (len(a) // bpp), largest


def label(row):
    if row["technique"] == "boulanger" and params(row).get("ground_shadows") == "false":
        return "boulanger (shadows off)"
    return row["technique"]


def model(folders):
    """Measured / model on the canonical scenes. Where the sweeps drew one size, a cell holds
    each process's (sweep folder's) ratio, in the order given; where they drew several, each
    process has a line under its technique and a cell holds the sizes, smallest first."""
    processes = [runs(f) for f in folders]
    labels = list(dict.fromkeys(label(r) for r in processes[0]))
    sizes = sorted({int(r["width"]) for r in processes[0]})

    def ratios(rows, name, scene):
        return [num(r, "model_ratio") for w in sizes for r in rows
                if label(r) == name and r["scene"] == scene and int(r["width"]) == w]

    print("| technique | meadow | football field | prairie flyover |\n|---|---|---|---|")
    for name in labels:
        if len(sizes) == 1:
            cells = [", ".join(f"{v:.2f}" for rows in processes for v in ratios(rows, name, scene))
                     for scene in SCENES]
            print(f"| {name} | " + " | ".join(cells) + " |")
            continue
        for i, rows in enumerate(processes):
            cells = [" / ".join(f"{v:.2f}" for v in ratios(rows, name, scene)) for scene in SCENES]
            print(f"| {name if i == 0 else ''} | " + " | ".join(cells) + " |")
    print()
    for folder, rows in zip(folders, processes):
        ratios = [num(r, "model_ratio") for r in rows]
        print(f"{folder}: {sum(map(within, ratios))} of {len(ratios)} within ±25 %, {span(ratios)}")
    for name in labels:
        ratios = [num(r, "model_ratio") for rows in processes for r in rows if label(r) == name]
        print(f"{name}: {sum(map(within, ratios))} of {len(ratios)}, {span(ratios)}")


def msaa(folder):
    """One process drawing each technique single-sampled and with 4x MSAA."""
    rows = runs(folder)
    print("| technique | scene | measured / model, single-sampled | with 4x MSAA | change | "
          "counted fragments a triangle (single / MSAA) | kept per counted fragment (single / MSAA) |")
    print("|---|---|---|---|---|---|---|")
    for technique, scene in sorted({(r["technique"], r["scene"]) for r in rows}):
        pair = [next(r for r in rows if r["technique"] == technique and r["scene"] == scene
                     and r["msaa"] == m) for m in ("false", "true")]
        ratio = [num(r, "model_ratio") for r in pair]
        ms = [num(r, "gpu_wall_ms_median") for r in pair]
        per_triangle = [num(r, "fragment_invocations") / num(r, "clipper_primitives_out") for r in pair]
        kept = [num(r, "fragments_passed") / num(r, "fragment_invocations") for r in pair]
        print(f"| {technique} | {scene} | {ratio[0]:.2f} ({ms[0]:.1f} ms) | {ratio[1]:.2f} "
              f"({ms[1]:.1f} ms) | {ratio[1] / ratio[0]:.2f}x | {per_triangle[0]:.1f} / "
              f"{per_triangle[1]:.1f} | {kept[0]:.3f} / {kept[1]:.3f} |")


def frames(folder):
    with open(ROOT / folder / "frames.csv", newline="") as f:
        return list(csv.DictReader(f))


def jahrmann(folder):
    """The density sweep: jahrmann with and without its levels against the reference."""
    rows, frame_rows = runs(folder), frames(folder)
    print("| blades | reference ms | jahrmann ms | speed-up (95 %) | lod off ms | speed-up | "
          "µs per blade: reference / jahrmann | compute ms (ns a blade) |")
    print("|---|---|---|---|---|---|---|---|")
    for variant in dict.fromkeys(r["scene_variant"] for r in rows):
        group = [r for r in rows if r["scene_variant"] == variant]
        reference = next(r for r in group if r["technique"] == "reference")
        levels = next(r for r in group if r["technique"] == "jahrmann" and params(r).get("lod") != "false")
        flat = next(r for r in group if r["technique"] == "jahrmann" and params(r).get("lod") == "false")
        blades = int(reference["blades_drawn"])
        ms = lambda r: num(r, "gpu_wall_ms_median")
        # What the frame spends outside its timestamped render passes: the compute pass.
        compute = statistics.median(
            float(f["gpu_wall_ms"]) - float(f["gpu_ts_render_ms"]) - float(f["gpu_ts_background_ms"])
            for f in frame_rows if f["run_id"] == levels["run_id"])
        speedup = lambda r, d: (f"{num(r, 'speedup'):.1f}x ({num(r, 'speedup_ci_low'):.{d}f}-"
                                f"{num(r, 'speedup_ci_high'):.{d}f})")
        group_digits = lambda n: f"{n:,.0f}".replace(",", " ")
        print(f"| {group_digits(blades)} | {group_digits(ms(reference))} | {group_digits(ms(levels))} | "
              f"{speedup(levels, 1)} | {group_digits(ms(flat))} | {speedup(flat, 2)} | "
              f"{ms(reference) / blades * 1e3:.2f} / {ms(levels) / blades * 1e3:.2f} | "
              f"{compute:.1f} ({compute / blades * 1e6:.0f}) |")


def zhang_target(folder):
    """zhang's speed-up over the reference of the same repetition, by option."""
    rows = runs(folder)
    groups = {}
    for row in rows:
        if row["technique"] != "zhang":
            continue
        reference = next(r for r in rows if r["technique"] == "reference"
                         and r["scene"] == row["scene"] and r["repetition"] == row["repetition"])
        p = params(row)
        key = (row["scene"], p.get("sorting"), p.get("trim_wings"))
        groups.setdefault(key, []).append((
            num(reference, "gpu_wall_ms_median") / num(row, "gpu_wall_ms_median"),
            num(reference, "frame_ms_median") / num(row, "frame_ms_median")))
    print("| scene | zhang's options | GPU wall | by repetition | frame |\n|---|---|---:|---:|---:|")
    for (scene, sorting, trim), values in groups.items():
        gpu = [g for g, _ in values]
        frame = [f for _, f in values]
        options = f"{'sort' if sorting == 'sort' else 'alpha to coverage'}, " \
                  f"{'wings cut' if trim == 'true' else 'whole wings'}"
        print(f"| {scene.replace('_', ' ')} | {options} | {statistics.median(gpu):.1f}x | "
              f"{min(gpu):.1f}-{max(gpu):.1f}x | {statistics.median(frame):.1f}x |")


def main(argv):
    if len(argv) < 2 or argv[0] not in ("diff", "model", "msaa", "jahrmann", "zhang_target"):
        sys.exit(__doc__)
    command, folders = argv[0], argv[1:]
    if command == "diff":
        rev = "HEAD"
        if "--rev" in folders:
            i = folders.index("--rev")
            rev = folders[i + 1]
            folders = folders[:i] + folders[i + 2:]
        for folder in folders:
            diff(folder, rev)
    elif command == "model":
        model(folders)
    else:
        {"msaa": msaa, "jahrmann": jahrmann, "zhang_target": zhang_target}[command](folders[0])


if __name__ == "__main__":
    main(sys.argv[1:])
