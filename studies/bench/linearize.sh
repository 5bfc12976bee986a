#!/usr/bin/env bash
# Linearisation's cost (issue 21): bench-linearize's medians (ns per call, native) and the
# instructions per call counted inside the API function (valgrind callgrind --toggle-collect),
# for every row: A, B, C, D of the plant and the inverse side's Jacobian, massless and full.
# With --reference BIN (a bench-linearize built from an older commit, e.g. by
# `git checkout OLD -- csrc && cmake --build build --target bench-linearize`, copied away, then
# `git checkout HEAD -- csrc`), the same for it in the same run, side by side, with the ratios.
# usage: studies/bench/linearize.sh [--calls N (200, under callgrind)] [--reference BIN]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
calls=200
reference=""
while (($#)); do
  case "$1" in
    --calls) calls="$2"; shift 2 ;;
    --reference) reference="$2"; shift 2 ;;
    *) echo "linearize.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
nice -n 10 cmake --build "$repo/build" -j2 --target bench-linearize >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
current="$repo/build/bench-linearize"
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"

# Median ns of one row (20000 calls) of a bench binary.
median_ns() { "$1" "$2" 20000 | awk -v r="$2" '$1 == r {print $3}'; }
# Instructions per call of one row inside its API function.
instructions() {
  local f=stewart_linearize_plant
  [[ $2 == inverse* ]] && f=stewart_linearize_inverse
  valgrind --tool=callgrind --toggle-collect="$f" --callgrind-out-file="$work/cg.out" \
    "$1" "$2" "$calls" >/dev/null 2>&1
  awk -v n="$calls" '/^totals:/ {printf "%d", $2 / n}' "$work/cg.out"
}

rows=(plant-massless plant-full inverse-massless inverse-full)
if [ -z "$reference" ]; then
  "$current"
  echo "instructions per call (callgrind, inside the API function, $calls calls):"
  for row in "${rows[@]}"; do printf '%-18s %12d\n' "$row" "$(instructions "$current" "$row")"; done
  exit 0
fi
echo "median ns (20000 calls, the two builds alternating row by row) and instructions per call"
echo "(callgrind, inside the API function, $calls calls); reference: $reference"
printf '%-18s %12s %12s %7s %14s %14s %7s\n' row ref-median median ratio ref-instr instr ratio
for row in "${rows[@]}"; do
  a=$(median_ns "$reference" "$row"); b=$(median_ns "$current" "$row")
  ia=$(instructions "$reference" "$row"); ib=$(instructions "$current" "$row")
  printf '%-18s %12s %12s %7.2f %14d %14d %7.2f\n' "$row" "$a" "$b" "$(echo "$a / $b" | bc -l)" \
    "$ia" "$ib" "$(echo "$ia / $ib" | bc -l)"
done
