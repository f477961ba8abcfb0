#!/usr/bin/env python3
"""The coverage checks of this folder's calibrations as Markdown tables (README.md's).

    python3 results/cost_model/coverage/table.py
"""
import glob
import os
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
files = sorted(glob.glob(os.path.join(HERE, "*.toml")))
data = {os.path.basename(f)[:-5]: tomllib.load(open(f, "rb")) for f in files}
tags = list(data)
checks = lambda tag: data[tag]["unit_costs"]["checks"]
names = [c["check"] for c in checks(tags[0])]
half = len(names) // 2

print("| check | size | " + " | ".join(tags) + " |")
print("|---|---|" + "---|" * len(tags))
for i, name in enumerate(names):
    size = ("4 layers" if i < half else "16 layers") if name.startswith("hidden") else (
        "4 000 blades" if i < half else "16 000 blades")
    print(f"| {name} | {size} | " + " | ".join(f"{checks(t)[i]['ratio']:.2f}" for t in tags) + " |")
print()
print("| check | " + " | ".join(f"{t}: fragments / primitive, kept / fragment" for t in tags if t.endswith("_a")) + " |")
print("|---|" + "---|" * sum(t.endswith("_a") for t in tags))
for i, name in enumerate(names[:half]):
    cells = []
    for t in tags:
        if not t.endswith("_a"):
            continue
        c = checks(t)[i]
        cells.append(f"{c['fragments'] / max(c['primitives'], 1):.1f}, {c['kept_per_fragment']:.3f}")
    print(f"| {name} | " + " | ".join(cells) + " |")
print()
for t in tags:
    u = data[t]["unit_costs"]
    v = lambda k: u[k]["value"]
    print(f"- `{t}`: primitive {v('primitive_ns'):.0f} ns, fragment opaque / alpha-tested / blended "
          f"{v('fragment_opaque_ns'):.2f} / {v('fragment_alpha_tested_ns'):.2f} / {v('fragment_blended_ns'):.2f} ns, "
          f"fit residual {100 * u['fit']['relative_rms_residual']:.1f} %, other processes {u.get('host_other_cores', 0):.3f} cores, "
          f"{data[t]['provenance']['date']}")
