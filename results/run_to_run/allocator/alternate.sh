#!/bin/bash
export XDG_RUNTIME_DIR=/tmp/grassbench-runtime-0
T=glibc.malloc.trim_threshold=1073741824:glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=67108864
for mode in sys keep keep sys sys keep; do
 for scene in football_field meadow prairie_flyover; do
  for tech in reference zhang boulanger bakay perbet jahrmann; do
    out=/tmp/slow/ab2/$mode.$scene.$tech; rm -rf $out; mkdir -p /tmp/slow/ab2
    if [ $mode = keep ]; then E="GLIBC_TUNABLES=$T"; else E="X=1"; fi
    env $E /usr/bin/time -f "%e %U %S" -o $out.time /work/main/target/release/grassbench run -t $tech -s $scene --size 640x360 --frames 8 --warmup 4 --no-calibration -o $out > $out.log 2>&1
    ms=$(python3 -c "import csv;print(list(csv.DictReader(open('$out/$scene/runs.csv')))[0]['gpu_wall_ms_median'])")
    echo "$mode $scene $tech $ms $(cat $out.time)"
    rm -rf $out
  done
 done
done
