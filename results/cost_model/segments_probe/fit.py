#!/usr/bin/env python3
"""The reference's segments probe: measured = a + b·(primitive + vertex terms) + c·(the vertex
stage's operations: transcendental + arithmetic terms), least squares over the runs (the
primitive terms include the primitives' fragment input slots where the runs price them). b and c
are factors on the model's own prices (1 = priced right); a is the frame's part that does not
grow with segments. Python 3, standard library only: python3 fit.py RESULTS_DIR..."""
import csv
import sys


def lstsq(X, y):
    n = len(X[0])
    M = [[sum(x[i] * x[j] for x in X) for j in range(n)] + [sum(x[i] * t for x, t in zip(X, y))]
         for i in range(n)]
    for i in range(n):
        p = max(range(i, n), key=lambda k: abs(M[k][i]))
        M[i], M[p] = M[p], M[i]
        for k in range(n):
            if k != i:
                c = M[k][i] / M[i][i]
                M[k] = [a - c * b for a, b in zip(M[k], M[i])]
    return [M[i][n] / M[i][i] for i in range(n)]


for folder in sys.argv[1:]:
    rows = list(csv.DictReader(open(f"{folder}/runs.csv")))
    X, y = [], []
    print(f"{folder}\n")
    print("| segments | triangles | vertices | transcendentals a vertex | measured ms | model ms "
          "| measured / model | primitives + vertices, model ms | vertex operations, model ms |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        f = lambda k: float(r[k] or 0)
        seg = dict(kv.split("=", 1) for kv in r["params"].split(";"))["segments"]
        # A primitive's fragment input slots are part of its price (a term since `de20c67`;
        # empty in older runs).
        base = f("model_primitive_ms") + f("model_primitive_input_ms") + f("model_vertex_ms")
        ops = f("model_vertex_transcendental_ms") + f("model_vertex_arithmetic_ms")
        X.append((1.0, base, ops))
        y.append(f("gpu_wall_ms_median"))
        print(f"| {seg} | {int(f('clipper_primitives_out'))} | {int(f('vertex_invocations'))} "
              f"| {f('vertex_transcendentals') / f('vertex_invocations'):.0f} | {y[-1]:.1f} "
              f"| {f('model_ms'):.1f} | {y[-1] / f('model_ms'):.2f} | {base:.1f} | {ops:.1f} |")
    a, b, c = lstsq(X, y)
    res = [t - a - b * x[1] - c * x[2] for x, t in zip(X, y)]
    print(f"\nfit: {a:.1f} ms + {b:.2f} x (primitives + vertices as priced) + {c:.2f} x (vertex "
          f"operations as priced); residuals {', '.join(f'{e:+.1f}' for e in res)} ms\n")
