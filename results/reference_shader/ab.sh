#!/bin/bash
# A/B of two grassbench builds on one technique alone (the reference unless named):
#   ./ab.sh OLD_BINARY NEW_BINARY [ROUNDS] [TECHNIQUE]
# Each round runs both builds (in turn, the first build alternating) on the three canonical
# scenes at their own size, 10 frames after 3 warm-up, one process a run, no calibration;
# prints one line a run: round, build, scene, GPU wall ms (median), frame ms (median),
# fragment invocations, clipper primitives, and a checksum of the last captured frame.
set -euo pipefail
old=$1; new=$2; rounds=${3:-4}; technique=${4:-reference}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/grassbench-runtime-$(id -u)}
mkdir -p -m 700 "$XDG_RUNTIME_DIR"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for round in $(seq 1 "$rounds"); do
  if [ $((round % 2)) = 1 ]; then order="old new"; else order="new old"; fi
  for build in $order; do
    if [ $build = old ]; then bin=$old; else bin=$new; fi
    for scene in football_field meadow prairie_flyover; do
      out=$tmp/$build.$scene
      "$bin" run -t "$technique" -s "$scene" --frames 10 --warmup 3 --no-calibration --out "$out" --force > /dev/null 2>&1
      python3 - "$out" "$round" "$build" "$scene" "$technique" <<'PY'
import csv, glob, hashlib, sys
out, round_, build, scene, technique = sys.argv[1:]
r = next(csv.DictReader(open(f"{out}/runs.csv")))
last = sorted(glob.glob(f"{out}/{scene}/{technique}_frame*.png"))[-1]
digest = hashlib.sha256(open(last, "rb").read()).hexdigest()[:12]
print(round_, build, scene, r["gpu_wall_ms_median"], r["frame_ms_median"],
      r["fragment_invocations"], r["clipper_primitives_out"], digest, flush=True)
PY
    done
  done
done
