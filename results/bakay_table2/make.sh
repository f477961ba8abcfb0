#!/usr/bin/env bash
# Bakay et al. 2002, Table 2, on this machine: experiments/bakay_table2.toml run by hand with
# `grassbench run`, one call per (shells, resolution), each into its own folder, plus the
# reference at both resolutions for the ratio. Run from the repository root:
#   bash results/bakay_table2/make.sh
# The machine may be shared: load averages before and after are recorded beside the results.
# Frame 3 (the first measured frame) is captured; PNGs are kept at 640x480 only (1024x768 ones
# are several MB each), and the background-only frames are dropped.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -p grassbench-cli
uptime > "results/bakay_table2/load_before.txt"
bin="${CARGO_TARGET_DIR:-target}/release/grassbench"
out=results/bakay_table2
mkdir -p -m 700 "${XDG_RUNTIME_DIR:=/tmp/grassbench-runtime-$(id -u)}"
export XDG_RUNTIME_DIR

run() { # folder, size, grassbench run arguments...
    local dir="$out/$1" size="$2"
    shift 2
    # CPU time of the whole process (start-up, 3 warm-up and 15 measured frames, lavapipe's
    # threads included): unlike wall time, barely affected by other work on a shared machine.
    mkdir -p "$dir"
    /usr/bin/time -f "%U %S %e" -o "$dir.cpu_time" \
        "$bin" run -s meadow --size "$size" --warmup 3 --frames 15 --capture 3 -o "$dir" --force "$@"
    mv "$dir.cpu_time" "$dir/cpu_time.txt"
    rm -f "$dir"/meadow/none_frame*.png
    if [ "$size" != 640x480 ]; then rm -f "$dir"/meadow/*.png; fi
}

for size in 640x480 1024x768; do
    for shells in 1 9 17 33 65; do
        run "shells${shells}_${size}" "$size" -t bakay -p "shells=$shells"
    done
    run "reference_${size}" "$size" -t reference
done

# Issue 3's target: 16 shells against the reference on the meadow at 1280x720.
run "target_shells16_1280x720" 1280x720 -t bakay -p shells=16
run "target_reference_1280x720" 1280x720 -t reference

# The table beside the paper's (README.md quotes it).
uptime > "$out/load_after.txt"
python3 "$out/table.py" > "$out/table.md"
