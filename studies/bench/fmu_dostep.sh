#!/usr/bin/env bash
# The FMU doStep against the library call it wraps (issue 22: within 5 %), before and after in one
# run: for FMI 2 and 3 and each fidelity, the StewartPlatform unit of a reference build
# (studies/bench/reference.sh) and of this tree's build/ are driven by this tree's harness
# (build/fmu_bench: set the inputs, doStep, read the outputs, along the combined cue's pose with
# its derivatives) under callgrind, counting inside fmiXDoStep only, for derivatives = 1 (Taylor
# advance) and 0 (finite differences, the default). Per call it prints the doStep's instructions,
# those of stewart_inverse_solve inside it (the same calls' library work, so the difference is the
# FMU's own), the difference and its share of the library call; then the median µs per doStep of
# both builds (fmu_bench, 20,000 steps, the median of three alternating runs).
# usage: studies/bench/fmu_dostep.sh [--commit C (6862cdd)] [--calls N (2000)]
#                                    [--derivatives "D ..." ("1 0")] [--prebuilt]
# --prebuilt: take the reference build .cache/reference-C/build as it stands (one shared by several
# worktrees, built already) instead of bringing it up to date with studies/bench/reference.sh.
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
commit=6862cdd; calls=2000; derivatives_list="1 0"; prebuilt=0
while (($#)); do
  case "$1" in
    --commit) commit="$2"; shift 2 ;;
    --calls) calls="$2"; shift 2 ;;
    --derivatives) derivatives_list="$2"; shift 2 ;;
    --prebuilt) prebuilt=1; shift ;;
    *) echo "fmu_dostep.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
if ((prebuilt)); then
  ref="$repo/.cache/reference-$commit"
  [ -f "$ref/build/fmu/StewartPlatform/fmi2/StewartPlatform.so" ] ||
    { echo "fmu_dostep.sh: no prebuilt reference build in $ref" >&2; exit 2; }
else
  ref="$(bash "$repo/studies/bench/reference.sh" "$commit")"
fi
nice -n 10 cmake --build "$repo/build" -j2 --target fmu_bench StewartPlatform_fmu2 \
  StewartPlatform_fmu3 >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
POSE="0,0.05,3,0.1,0,0.04,2,0.7,0.5,0.03,4,0.3,0,0.10,2.5,1.1,0,0.08,3.5,0.4,0,0.15,1.5,0.9"

# "doStep library" instructions per call (inclusive) for build dir, FMI version, fidelity.
counts() {
  local b="$1" v="$2" fidelity="$3" file="$work/cg.out"
  valgrind --tool=callgrind --toggle-collect="fmi${v}DoStep" --callgrind-out-file="$file" \
    "$repo/build/fmu_bench" "$b/fmu/StewartPlatform/fmi$v/StewartPlatform.so" --fmi "$v" \
    --fidelity "$fidelity" --derivatives "$derivatives" --step 0.001 \
    --duration "$(echo "$calls / 1000" | bc -l)" --pose "$POSE" >/dev/null 2>&1
  callgrind_annotate --inclusive=yes --threshold=100 "$file" 2>/dev/null | tr -d ',' | awk -v n="$calls" '
    /:fmi[23]DoStep / && !d { d = $1 } /:stewart_inverse_solve / && !l { l = $1 }
    END { printf "%d %d", d / n, l / n }'
}

echo "fmiXDoStep of StewartPlatform vs stewart_inverse_solve inside it: reference $commit vs this" \
     "tree ($(git -C "$repo" log -1 --format=%h)$(git -C "$repo" diff --quiet HEAD || echo ', uncommitted changes'))"
echo "$(date -u '+%Y-%m-%d %H:%M UTC'); callgrind, instructions per call over $calls calls;" \
     "load $(cut -d' ' -f1-3 /proc/loadavg)"
name=(kinematic massless full)
printf '%-3s %-4s %-10s | %9s %9s %7s %7s | %9s %9s %7s %7s\n' der FMI fidelity "ref call" \
  "ref lib" "ref +" "ref %" "now call" "now lib" "now +" "now %"
for derivatives in $derivatives_list; do
  for v in 2 3; do
    for fidelity in 0 1 2; do
      read -r rd rl <<<"$(counts "$ref/build" "$v" "$fidelity")"
      read -r nd nl <<<"$(counts "$repo/build" "$v" "$fidelity")"
      printf '%-3s %-4s %-10s | %9d %9d %7d %6.1f%% | %9d %9d %7d %6.1f%%\n' "$derivatives" "$v" \
        "${name[$fidelity]}" "$rd" "$rl" $((rd - rl)) "$(echo "100 * ($rd - $rl) / $rl" | bc -l)" \
        "$nd" "$nl" $((nd - nl)) "$(echo "100 * ($nd - $nl) / $nl" | bc -l)"
    done
  done
done

# Median µs per doStep of one run of fmu_bench (20,000 steps of 1 ms).
median() {
  local b="$1" v="$2" fidelity="$3" derivatives="$4"
  "$repo/build/fmu_bench" "$b/fmu/StewartPlatform/fmi$v/StewartPlatform.so" --fmi "$v" \
    --fidelity "$fidelity" --derivatives "$derivatives" --step 0.001 --duration 20 \
    --pose "$POSE" | tr ' ' '\n' | sed -n 's/^doStep_us_median=//p'
}
middle() { printf '%s\n' "$@" | sort -g | sed -n 2p; }
echo "median µs per doStep (fmu_bench, 20,000 steps, median of three alternating runs; load" \
     "$(cut -d' ' -f1-3 /proc/loadavg))"
printf '%-3s %-4s %-10s | %8s %8s\n' der FMI fidelity ref now
for derivatives in $derivatives_list; do
  for v in 2 3; do
    for fidelity in 0 1 2; do
      r=(); n=()
      for _ in 1 2 3; do
        r+=("$(median "$ref/build" "$v" "$fidelity" "$derivatives")")
        n+=("$(median "$repo/build" "$v" "$fidelity" "$derivatives")")
      done
      printf '%-3s %-4s %-10s | %8.3f %8.3f\n' "$derivatives" "$v" "${name[$fidelity]}" \
        "$(middle "${r[@]}")" "$(middle "${n[@]}")"
    done
  done
done
