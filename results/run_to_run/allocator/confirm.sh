#!/bin/bash
# The shipped build (run from the repository root): the reference's pitch and flyover at
# 640x360, 8 frames after 4, each in its own process, with glibc's defaults
# (GRASSBENCH_ALLOCATOR=system) and with the heaps kept (grassbench's own setting), alternated;
# then one process of each under `strace -f -c` for the allocator's system calls.
# Prints: mode scene median-GPU-ms wall-s user-s system-s
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/grassbench-runtime-0}
bin=${GRASSBENCH:-target/release/grassbench}
out=$(mktemp -d)
echo "# revision $(git rev-parse --short=12 HEAD), $(date -u +%FT%TZ)"
for round in 1 2 3; do
  for mode in system kept; do
    for scene in football_field prairie_flyover; do
      env $([ $mode = system ] && echo GRASSBENCH_ALLOCATOR=system) /usr/bin/time -f "%e %U %S" -o $out/time \
        $bin run -t reference -s $scene --size 640x360 --frames 8 --warmup 4 --no-calibration -o $out/run --force >/dev/null 2>&1
      ms=$(python3 -c "import csv;print(round(float(list(csv.DictReader(open('$out/run/$scene/runs.csv')))[0]['gpu_wall_ms_median']),1))")
      echo "$mode $scene $ms $(cat $out/time)"
    done
  done
done
for mode in system kept; do
  env $([ $mode = system ] && echo GRASSBENCH_ALLOCATOR=system) strace -f -c -o $out/strace \
    $bin run -t reference -s football_field --size 640x360 --frames 8 --warmup 4 --no-calibration -o $out/run --force >/dev/null 2>&1
  echo "# strace -f -c, $mode, the pitch: calls of mprotect, munmap, mmap, brk"
  grep -E " (mprotect|munmap|mmap|brk)$" $out/strace | awk '{print "#   " $NF, $4}'
done
rm -rf $out
