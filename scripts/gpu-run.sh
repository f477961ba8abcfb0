#!/usr/bin/env bash
# The measurements for a machine with a GPU and no Rust toolchain (issue 24 §4): with a
# stripped release binary beside the repository's files, one command calibrates the adapter
# (its unit costs, the vertex stage's texel loads among them), runs
# the default comparison at 1280x720 and 1920x1080, the image comparison, and the cost
# model's sweep, into results/gpu-<adapter>/ with each step's provenance (every folder's
# meta.toml: adapter, driver, backend, revision, command line) and a log of what ran.
#
# Build the binary where the toolchain is (x86-64), then copy it and this repository there:
#   cargo build --release -p grassbench-cli && strip -o grassbench target/release/grassbench
#   scripts/gpu-run.sh                       # on the GPU machine, from the repository's root
#
# Settings (environment):
#   GRASSBENCH          the binary (default: ./grassbench, else target/release/grassbench, else
#                       `grassbench` on PATH)
#   GPU_RUN_SIZES       sizes of the default comparison (default "1280x720 1920x1080")
#   GPU_RUN_FRAMES      measured frames per run (default 20; 3 warm-up frames before them)
#   GPU_RUN_SCENES      scenes of the comparison and of `compare` (default "default": the three
#                       canonical scenes)
#   GPU_RUN_MOTION      frames along each camera motion in `compare` (default 24)
#   GPU_RUN_SWEEPS      sweep files run after the comparison (default: experiments/cost_model.toml
#                       and experiments/papers.toml where they exist)
#   GPU_RUN_OUT         the results folder (default results/gpu-<adapter>)
#   GRASSBENCH_BACKEND  the API (vulkan, metal, dx12, gl; default: the best the machine has)
# A step that fails is logged and the next runs; the script's status is the first failure's.
set -uo pipefail
cd "$(dirname "$0")/.."

bin=${GRASSBENCH:-}
if [[ -z $bin ]]; then
  for b in ./grassbench target/release/grassbench; do
    [[ -x $b ]] && { bin=$b; break; }
  done
  bin=${bin:-grassbench}
fi
command -v "$bin" >/dev/null || {
  echo "gpu-run: no grassbench binary: build one (see this script's header) or set GRASSBENCH" >&2
  exit 2
}
read -r -a sizes <<<"${GPU_RUN_SIZES:-1280x720 1920x1080}"
frames=${GPU_RUN_FRAMES:-20}
scenes=${GPU_RUN_SCENES:-default}
motion=${GPU_RUN_MOTION:-24}
if [[ -n ${GPU_RUN_SWEEPS+set} ]]; then
  read -r -a sweeps <<<"$GPU_RUN_SWEEPS"
else
  sweeps=()
  for s in experiments/cost_model.toml experiments/papers.toml; do
    [[ -f $s ]] && sweeps+=("$s")
  done
fi
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/grassbench-runtime-$(id -u)}
mkdir -p -m 700 "$XDG_RUNTIME_DIR"

# The adapter names the folder: calibrate first, into a scratch file, and read its name.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
"$bin" calibrate --size "${sizes[0]}" -o "$scratch/calibration.toml" || {
  echo "gpu-run: calibration failed: no adapter? (see above)" >&2
  exit 2
}
adapter=$(awk '/^\[(provenance\.)?adapter\]/{a=1; next} /^\[/{a=0} a && /^name = /{sub(/^name = "/,""); sub(/"$/,""); print; exit}' "$scratch/calibration.toml")
slug=$(printf '%s' "${adapter:-unknown}" | tr 'A-Z' 'a-z' | sed -E 's/[^a-z0-9]+/-/g; s/^-+|-+$//g' | cut -c1-48)
out=${GPU_RUN_OUT:-results/gpu-$slug}
mkdir -p "$out"
cp "$scratch/calibration.toml" "$out/calibration_${sizes[0]}.toml"
log=$out/gpu-run.log
echo "gpu-run: $adapter -> $out ($(date -u +%FT%TZ))" | tee "$log"

status=0
step() {
  local started=$SECONDS
  echo "== $*" | tee -a "$log"
  if "$@" 2>&1 | tee -a "$log"; then
    echo "== done in $((SECONDS - started)) s" | tee -a "$log"
  else
    echo "== FAILED after $((SECONDS - started)) s: $*" | tee -a "$log"
    [[ $status -eq 0 ]] && status=1
  fi
}

for size in "${sizes[@]:1}"; do
  step "$bin" calibrate --size "$size" -o "$out/calibration_$size.toml"
done
for size in "${sizes[@]}"; do
  step "$bin" run --technique all --scene "$scenes" --size "$size" --frames "$frames" \
    --warmup 3 --out "$out/default_$size" --force
done
step "$bin" compare --scene "$scenes" --size "${sizes[0]}" --motion-frames "$motion" \
  --out "$out/compare" --force
for sweep in "${sweeps[@]}"; do
  name=$(basename "$sweep" .toml)
  step "$bin" sweep "$sweep" -o "$out/$name"
  step "$bin" report "$out/$name"
done
echo "gpu-run: finished ($(date -u +%FT%TZ)), status $status; the log is $log" | tee -a "$log"
exit "$status"
