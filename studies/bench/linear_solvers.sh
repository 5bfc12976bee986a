#!/usr/bin/env bash
# The core's linear solvers against SUNDIALS' KLU and Eigen on the full step's systems
# (csrc/bench/bench_linear.cpp): median times from one native run, then instructions per
# factorisation + transposed solve, callgrind counted inside each variant's function.
# usage: studies/bench/linear_solvers.sh [OUT (build/linear-solvers.txt)] [CALLS (400)]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
out="${1:-$repo/build/linear-solvers.txt}"; calls="${2:-400}"
nice -n 10 cmake --build "$repo/build" -j2 --target bench-linear >&2
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
{
  "$repo/build/bench-linear"
  echo "instructions per factorisation + transposed solve (callgrind, $calls calls, inside the call):"
  for variant in linear_block linear_block_groups linear_block_2 linear_block_4 linear_block_8 \
                 linear_dense linear_klu linear_eigen_sparse linear_eigen_dense; do
    if valgrind --tool=callgrind --toggle-collect="$variant" --callgrind-out-file="$work/cg" \
         "$repo/build/bench-linear" "$variant" "$calls" >/dev/null 2>&1; then
      printf '  %-20s %10d\n' "$variant" "$(( $(awk '/^totals:/ {print $2}' "$work/cg") / calls ))"
    else  # the kernel does not run on this CPU
      printf '  %-20s %10s\n' "$variant" "not run"
    fi
  done
} | tee "$out"
