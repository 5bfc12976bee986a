#!/usr/bin/env bash
# Linearisation's cost (issue 21): bench-linearize's medians (ns per call, native) and the
# instructions per call counted inside the API function (valgrind callgrind --toggle-collect),
# for every row: A, B, C, D of the plant and the inverse side's Jacobian, massless and full.
# usage: studies/bench/linearize.sh [--calls N (200, under callgrind)]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
calls=200
[ "${1:-}" = "--calls" ] && calls="$2"
nice -n 10 cmake --build "$repo/build" -j2 --target bench-linearize >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
"$repo/build/bench-linearize"
echo "instructions per call (callgrind, inside the API function, $calls calls):"
for row in plant-massless plant-full inverse-massless inverse-full; do
  f=stewart_linearize_plant
  [[ $row == inverse* ]] && f=stewart_linearize_inverse
  valgrind --tool=callgrind --toggle-collect="$f" --callgrind-out-file="$work/cg.out" \
    "$repo/build/bench-linearize" "$row" "$calls" >/dev/null 2>&1
  printf '%-18s %12d\n' "$row" "$(awk -v n="$calls" '/^totals:/ {printf "%d", $2 / n}' "$work/cg.out")"
done
