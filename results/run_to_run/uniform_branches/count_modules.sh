#!/bin/bash
# Counts the LLVM modules lavapipe/llvmpipe creates while `grassbench run` draws one technique
# on the football field, 8 warm-up frames then 8 and then 24 measured ones, with Mesa's shader
# cache off: the difference over the 16 extra frames is the shader code compiled per frame
# (`src/shaders/branches.rs`). Needs gdb; run from the repository root after
# `cargo build --release`. Writes one line per technique and kind of module to stdout.
set -euo pipefail
bin=${GRASSBENCH:-target/release/grassbench}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/gdb" <<'GDB'
set pagination off
set breakpoint pending on
break LLVMModuleCreateWithNameInContext
commands
silent
x/s $rdi
continue
end
run
GDB
echo "technique,frames,module_kind,modules"
for t in ${TECHNIQUES:-reference zhang boulanger bakay perbet jahrmann}; do
  for f in 8 24; do
    MESA_SHADER_CACHE_DISABLE=true gdb -q -batch -x "$tmp/gdb" --args "$bin" run -t "$t" \
      -s football_field --size 320x180 --frames "$f" --warmup 8 --backend vulkan \
      --no-calibration --force -o "$tmp/out" 2>&1 |
      grep -o '"[a-z_]*[0-9]*_variant[0-9_]*"' | sed 's/[0-9]\+/N/g; s/"//g' | sort | uniq -c |
      awk -v t="$t" -v f="$f" '{print t "," f "," $2 "," $1}'
  done
done
