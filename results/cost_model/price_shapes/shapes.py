#!/usr/bin/env python3
"""Would a primitive priced in more parts by the size of its pass explain the runs better?

Refits each kept calibration (its `samples`, written by `grassbench calibrate -o`) with the
primitive priced in several shapes of the pass size n, and prices a sweep's runs with each fit.
The shapes, beside the primitive's own price p·n:

  one             no head term (the model before `3140b02`)
  step360         Δ·min(n, 360 000)                       (the shipped `head_primitive`)
  step90+360      Δ1·min(n, 90 000) + Δ2·min(n, 360 000)
  step45+180+720  three steps at 45 000, 180 000 and 720 000
  exp100k         Δ·S·(1 − e^(−n/S)), S = 100 000: a smooth fall of the marginal price
  exp200k         the same, S = 200 000
  hyp200k         Δ·n / (1 + n/S), S = 200 000

Fit as the harness fits (`src/cost/fit.rs`): non-negative least squares on relative errors over
every term jointly. A run's work is read back from its `model_*_ms` columns divided by the
unit costs (`meta.toml`) that priced it, so it is the work the model priced, background
included. Its pass sizes are not in the records: a run is taken as one segment of its
primitives, or, where its recorded head is below its primitives, as one large segment and the
rest (the background's, a few thousand) as one small one. Exact for one segment, an
approximation for a technique drawing several.

Needs numpy and scipy (`pip install numpy scipy`). Usage, from the repository root:

  python3 results/cost_model/price_shapes/shapes.py SWEEP_FOLDER CALIBRATION.toml...
"""
import csv
import sys
import tomllib
from pathlib import Path

import numpy as np
from scipy.optimize import nnls

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from tables import within  # noqa: E402  (results/tables.py: the shared helpers)

S0 = 360_000.0
SHAPES = {
    "one": lambda n: [],
    "step360": lambda n: [min(n, S0)],
    "step90+360": lambda n: [min(n, 90e3), min(n, S0)],
    "step45+180+720": lambda n: [min(n, 45e3), min(n, 180e3), min(n, 720e3)],
    "exp100k": lambda n: [100e3 * (1 - np.exp(-n / 100e3))],
    "exp200k": lambda n: [200e3 * (1 - np.exp(-n / 200e3))],
    "hyp200k": lambda n: [n / (1 + n / 200e3)],
}

# unit cost in meta.toml -> (runs.csv column, work key in a calibration sample)
TERMS = [
    ("fixed_ms", "model_fixed_ms", None),
    ("vertex_ns", "model_vertex_ms", "vertex_invocations"),
    ("primitive_ns", "model_primitive_ms", "primitives"),
    ("fragment_opaque_ns", "model_fragment_opaque_ms", "fragments_opaque"),
    ("fragment_alpha_tested_ns", "model_fragment_alpha_tested_ms", "fragments_alpha_tested"),
    ("fragment_blended_ns", "model_fragment_blended_ms", "fragments_blended"),
    ("draw_ns", "model_draw_ms", "draw_calls"),
    ("compute_invocation_ns", "model_compute_ms", "compute_invocations"),
    ("upload_ms_per_mb", "model_upload_ms", "upload_bytes"),
]
for stem, key in [
    ("texture_load", "texture_loads"), ("float_texture_load", "float_texture_loads"),
    ("vertex_texture_load", "vertex_texture_loads"),
    ("vertex_float_texture_load", "vertex_float_texture_loads"),
    ("texture_sample", "texture_samples"), ("float_texture_sample", "float_texture_samples"),
    ("vertex_transcendental", "vertex_transcendentals"),
    ("fragment_transcendental", "fragment_transcendentals"),
    ("compute_transcendental", "compute_transcendentals"),
    ("vertex_arithmetic", "vertex_arithmetic"), ("fragment_arithmetic", "fragment_arithmetic"),
    ("compute_arithmetic", "compute_arithmetic"), ("compute_barrier", "compute_barriers"),
    ("compute_storage", "compute_storage"), ("vertex_storage", "vertex_storage"),
    ("compute_division", "compute_divisions"), ("texture_mip_blend", "texture_mip_blends"),
    ("instance", "instances"), ("primitive_input", "primitive_inputs"),
    ("texture_explicit_level", "texture_explicit_levels"),
]:
    TERMS.append((stem + "_ns", f"model_{stem}_ms", key))
KEYS = [key for _, _, key in TERMS if key]


def per_unit(name):
    """Work units per ms of the unit cost's price: ns prices count units, ms/MB counts bytes."""
    return 1.0 if name == "fixed_ms" else 1e6


def load_runs(folder, size, msaa):
    """The runs drawn at `size` (WxH) with or without MSAA, each with the work it was priced on."""
    meta = tomllib.load(open(f"{folder}/meta.toml", "rb"))
    costs = [u for u in meta["unit_costs"] if u["msaa"] == msaa and u["size"] == size]
    if not costs:
        return []
    uc = costs[0]
    runs = []
    for r in csv.DictReader(open(f"{folder}/runs.csv")):
        if (r["msaa"] == "true") != msaa or f"{r['width']}x{r['height']}" != size:
            continue
        if not r["model_ms"]:
            continue
        work = {}
        for name, column, key in TERMS:
            price = uc[name]["value"]
            if key is None:
                continue
            if price > 0:
                work[key] = float(r[column] or 0) / price * per_unit(name)
            else:  # held at zero: no amount to read back; the run's own count where it has one
                work[key] = float(r.get(key) or 0)
        head_price = uc["head_primitive_ns"]["value"]
        work["head"] = (float(r["model_head_primitive_ms"] or 0) / head_price * 1e6
                        if head_price > 0 else float(r["head_primitives"] or 0))
        runs.append((r, work))
    return runs


def head_features(shape, n, head):
    """The shape's head amounts for a run of `n` primitives whose step-360k head was `head`."""
    if head < n - 0.5:  # one segment past S0 plus small ones (of `head - S0` in all)
        small = max(head - S0, 0.0)
        return [a + b for a, b in zip(shape(n - small), shape(small))]
    return shape(n)


def fit(samples, shape):
    """Unit costs (ms per unit) fitted to the calibration's samples with this head shape."""
    x, y = [], []
    for s in samples:
        w = s["sample"]["work"]
        x.append([1.0] + [w[k] for k in KEYS] + shape(w["primitives"]))
        y.append(s["sample"]["measured_ms"])
    x, y = np.array(x), np.array(y)
    weighted = x / y[:, None]
    scale = np.abs(weighted).max(axis=0)
    scale[scale == 0] = 1
    c, _ = nnls(weighted / scale, np.ones_like(y), maxiter=10_000)
    c = c / scale
    residual = (x @ c - y) / y
    return c, float(np.sqrt(np.mean(residual**2)))


def main(folder, calibrations):
    print("| calibration | shape | fit RMS | within ±25 % | " + " | ".join(
        ["reference", "zhang", "perbet", "bakay", "boulanger", "jahrmann"]) + " |")
    print("|---" * 10 + "|")
    for path in calibrations:
        cal = tomllib.load(open(path, "rb"))
        size, msaa = cal["unit_costs"]["size"], cal["unit_costs"]["msaa"]
        runs = load_runs(folder, size, msaa)
        for name, shape in SHAPES.items():
            c, rms = fit(cal["samples"], shape)
            by = {}
            for r, w in runs:
                x = [1.0] + [w[k] for k in KEYS] + head_features(shape, w["primitives"], w["head"])
                by.setdefault(r["technique"], []).append(
                    float(r["gpu_wall_ms_median"]) / float(np.dot(x, c)))
            ratios = [v for vs in by.values() for v in vs]
            within_band = sum(within(v) for v in ratios)
            cells = [f"{min(by[t]):.2f}-{max(by[t]):.2f}" if t in by else ""
                     for t in ["reference", "zhang", "perbet", "bakay", "boulanger", "jahrmann"]]
            label = path.split("/")[-1] + (" (4x MSAA)" if msaa else "")
            print(f"| {label} | {name} | {rms * 100:.1f} % | {within_band} of {len(ratios)} | "
                  + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
