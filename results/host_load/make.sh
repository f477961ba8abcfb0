#!/usr/bin/env bash
# Issue 19 §8: the same boulanger frame on the football field, measured in fresh processes
# with 0, 1 and 2 CPU-bound processes beside it (`busy` loops in the shell), three times each.
# Writes one `grassbench run` folder per measurement under results/host_load/runs/ and a
# summary table (summary.csv). Run from the repository root after `cargo build --release`.
set -euo pipefail
bin=${GRASSBENCH:-target/release/grassbench}
out=results/host_load
rm -rf "$out/runs"; mkdir -p "$out/runs"
echo "others,round,gpu_wall_ms_median,gpu_wall_ms_p5,gpu_wall_ms_p95,host_other_cores,host_steal" > "$out/summary.csv"
for round in 1 2 3; do
  for others in 0 1 2; do
    pids=()
    for _ in $(seq 1 "$others"); do (while :; do :; done) & pids+=($!); done
    dir="$out/runs/others${others}-round${round}"
    "$bin" run -t boulanger -s football_field --frames 10 --warmup 3 -o "$dir" --force 2>/dev/null
    for p in "${pids[@]}"; do kill "$p"; done
    python3 - "$dir/runs.csv" "$others" "$round" >> "$out/summary.csv" <<'PY'
import csv, sys
row = next(csv.DictReader(open(sys.argv[1])))
print(",".join([sys.argv[2], sys.argv[3]] + [row[k] for k in
      ["gpu_wall_ms_median", "gpu_wall_ms_p5", "gpu_wall_ms_p95", "host_other_cores", "host_steal"]]))
PY
  done
done
cat "$out/summary.csv"
