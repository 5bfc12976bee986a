#!/usr/bin/env bash
# The limit check and the axis ranges (issue 19's goals: <= 2 us and <= 100 us per pose): the
# medians bench-limits prints, and the instructions per call counted INSIDE each function by
# valgrind callgrind (--toggle-collect; bench-limits --check-only / --ranges-only make exactly N
# calls), for the thesis defaults and the vendor-like limits. Times on this shared machine are
# noisy (a preempted call shows as milliseconds in the p99 and max); the counts are not.
# usage: studies/bench/limits.sh [N (1000)]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
n="${1:-1000}"
nice -n 10 cmake --build "$repo/build" -j2 --target bench-limits >&2
bench="$repo/build/bench-limits"
"$bench" "$n"
"$bench" "$n" --vendor
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for limits in "" --vendor; do
  for what in check ranges; do
    valgrind --tool=callgrind --toggle-collect="stewart_limits_$what" \
      --callgrind-out-file="$work/cg.out" "$bench" "$n" $limits "--$what-only" >/dev/null 2>&1
    total="$(callgrind_annotate "$work/cg.out" | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')"
    printf "%-9s %-6s %12.0f instructions per call\n" "${limits:-thesis}" "$what" "$((total / n))"
  done
done
