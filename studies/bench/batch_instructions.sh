#!/usr/bin/env bash
# Instructions per pose of the inverse batch's kinematic and massless levels on each kernel
# (scalar: stewart_inverse_solve per row; portable; avx2 where the CPU has it), counted by
# callgrind inclusive of stewart::inverse_batch over one batch of ROWS rows of the combined cue
# (build/bench-batch ROWS --once LEVEL PATH). Instruction counts are stable on a loaded machine
# where times are not; build/bench-batch prints the medians.
# usage: studies/bench/batch_instructions.sh [BUILD_DIR (build)] [ROWS (2000)]
set -euo pipefail
build=${1:-build}
rows=${2:-2000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-10s %-9s %12s\n' level kernel "instr/pose"
for level in 0 1; do
  for path in scalar portable avx2; do
    if ! "$build/bench-batch" "$rows" --once "$level" "$path" >/dev/null 2>&1; then continue; fi
    valgrind --tool=callgrind --callgrind-out-file="$out/cg" "$build/bench-batch" "$rows" --once \
      "$level" "$path" >/dev/null 2>&1
    # the batch function itself, not its lambda (whose name starts alike)
    total=$(callgrind_annotate --inclusive=yes "$out/cg" | grep 'stewart::inverse_batch(' |
      grep -v lambda | head -1 | awk '{gsub(",", "", $1); print $1}')
    printf '%-10s %-9s %12d\n' "$([ "$level" = 0 ] && echo kinematic || echo massless)" "$path" \
      $((total / rows))
  done
done
