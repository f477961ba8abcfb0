#!/bin/bash
# `grassbench calibrate --size 640x360`, each in its own process, with glibc's defaults
# (GRASSBENCH_ALLOCATOR=system) and with the heaps kept, alternated, run from the repository
# root with the shipped build. Prints: mode raw-blade-ns triangles/s primitive-ns vertex-ns
# opaque-fragment-ns wall-s user-s system-s
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/grassbench-runtime-0}
bin=${GRASSBENCH:-target/release/grassbench}
out=$(mktemp -d)
echo "# revision $(git rev-parse --short=12 HEAD), $(date -u +%FT%TZ)"
for mode in system kept kept system system kept; do
  env $([ $mode = system ] && echo GRASSBENCH_ALLOCATOR=system) /usr/bin/time -f "%e %U %S" -o $out/time \
    $bin calibrate --size 640x360 -o $out/c.toml >/dev/null 2>&1
  python3 - "$mode" "$(cat $out/time)" "$out/c.toml" <<'PY'
import sys, tomllib
mode, time, path = sys.argv[1], sys.argv[2], sys.argv[3]
c = tomllib.load(open(path, "rb"))
raw = c["calibration"]
u = c["unit_costs"][0] if isinstance(c["unit_costs"], list) else c["unit_costs"]
v = lambda k: u[k]["value"] if isinstance(u[k], dict) else u[k]
print(mode, round(raw["raw_blade_cost_ns"], 1), round(raw["triangles_per_s"] / 1e6, 2),
      round(v("primitive_ns"), 1), round(v("vertex_ns"), 2), round(v("fragment_opaque_ns"), 2), time)
PY
done
rm -rf $out
