#!/usr/bin/env bash
# Instructions per pose of the inverse batch's kinematic and massless levels on each kernel
# (scalar: stewart_inverse_solve per row; portable; avx2 and avx512vl where the CPU has them),
# counted by callgrind inclusive of stewart::inverse_batch over one batch of ROWS rows of the combined cue
# (build/bench-batch ROWS --once LEVEL PATH). Instruction counts are stable on a loaded machine
# where times are not; build/bench-batch prints the medians (build/bench-batch ROWS --kernels: the
# kernels alone, with the fastest batch beside the median). With BEFORE (a bench-batch program of
# an older commit, e.g. one linked against a reference build's libstewart.a) a column for it
# beside.
# usage: studies/bench/batch_instructions.sh [BUILD_DIR (build)] [ROWS (2000)] [BEFORE]
set -euo pipefail
build=${1:-build}
rows=${2:-2000}
before=${3:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# instructions per pose of PROGRAM at LEVEL on PATH (empty if the program lacks the path)
per_pose() {
  if ! "$1" "$rows" --once "$2" "$3" >/dev/null 2>&1; then return; fi
  # (valgrind runs no AVX-512 and its CPUID hides it, so bench-batch refuses the avx512vl kernel
  # there: no count; studies/bench/step_count.sh counts it)
  valgrind --tool=callgrind --callgrind-out-file="$out/cg" "$1" "$rows" --once "$2" "$3" \
    >/dev/null 2>&1 || return 0
  # the batch function itself, not its lambda (whose name starts alike)
  total=$(callgrind_annotate --inclusive=yes "$out/cg" | grep 'stewart::inverse_batch(' |
    grep -v lambda | head -1 | awk '{gsub(",", "", $1); print $1}')
  echo $((total / rows))
}

if [ -n "$before" ]; then
  printf '%-10s %-9s %12s %12s\n' level kernel "before" "instr/pose"
else
  printf '%-10s %-9s %12s\n' level kernel "instr/pose"
fi
for level in 0 1; do
  name=$([ "$level" = 0 ] && echo kinematic || echo massless)
  for path in scalar portable avx2 avx512vl; do
    now=$(per_pose "$build/bench-batch" "$level" "$path")
    [ -n "$now" ] || continue
    if [ -n "$before" ]; then
      printf '%-10s %-9s %12s %12d\n' "$name" "$path" "$(per_pose "$before" "$level" "$path")" "$now"
    else
      printf '%-10s %-9s %12d\n' "$name" "$path" "$now"
    fi
  done
done
