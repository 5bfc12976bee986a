#!/usr/bin/env bash
# Issue 22's cost table, before and after, in one run: for every row, instructions per call
# counted INSIDE the API call (valgrind callgrind, --toggle-collect on the function below: the
# harness build/bench-calls makes exactly N calls of it) and the median time per call (the same
# harness run natively, and the medians printed by the existing bench programs), for a reference
# build of an older commit (studies/bench/reference.sh) and for this tree's build/ side by side.
# Writes the table and the bench programs' own reports to OUT.
# usage: studies/bench/instructions.sh [--commit C (171f04e)] [--out OUT (build/instructions.txt)]
#                                      [--calls N (2000)] [--median-calls N (20000)] [--no-benches]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"

# The API function each row counts inside: after a rename of the public API, edit here only.
declare -A FUNCTION=(
  [inverse-kinematic]=stewart_inverse_solve
  [inverse-massless]=stewart_inverse_solve
  [inverse-full]=stewart_inverse_solve
  [forward-tracking]=stewart_forward_solve
  [plant-massless]=stewart_plant_step
  [plant-full]=stewart_plant_step
  [fmu-dostep-kinematic]=fmi2DoStep
  [fmu-dostep-massless]=fmi2DoStep
  [fmu-dostep-full]=fmi2DoStep
)
# The same functions' names before the one grammar of issue 18 (a reference build older than it).
declare -A BEFORE_GRAMMAR=([stewart_inverse_solve]=stewart_solve)
ROWS=(inverse-kinematic inverse-massless inverse-full forward-tracking plant-massless plant-full
      fmu-dostep-kinematic fmu-dostep-massless fmu-dostep-full)

commit=171f04e; out="$repo/build/instructions.txt"; calls=2000; median_calls=20000; benches=1
while (($#)); do
  case "$1" in
    --commit) commit="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --calls) calls="$2"; shift 2 ;;
    --median-calls) median_calls="$2"; shift 2 ;;
    --no-benches) benches=0; shift ;;
    *) echo "instructions.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

ref="$(bash "$repo/studies/bench/reference.sh" "$commit")"
nice -n 10 cmake --build "$repo/build" -j2 --target bench-calls bench-closed-form bench-full \
  bench-forward bench-plant fmu_bench StewartPlatform_fmu2 >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# Instructions counted inside FUNCTION[row], divided by the number of calls.
per_call() {  # build_dir row
  local b="$1" row="$2" f="${FUNCTION[$2]}" n="$calls" file="$work/cg.out"
  if ! grep -q "$f" "$b/../csrc/include/stewart/"*.h && [ -n "${BEFORE_GRAMMAR[$f]:-}" ]; then
    f="${BEFORE_GRAMMAR[$f]}"
  fi
  case "$row" in
    fmu-dostep-*)
      local fidelity
      case "$row" in *kinematic) fidelity=0 ;; *massless) fidelity=1 ;; *) fidelity=2 ;; esac
      local so="$b/fmu/StewartPlatform/fmi2/StewartPlatform.so"
      # The combined cue (scenes/combined.json); duration / step = n doStep calls.
      valgrind --tool=callgrind --toggle-collect="$f" --callgrind-out-file="$file" \
        "$b/fmu_bench" "$so" --fidelity "$fidelity" --step 0.001 --duration "$(echo "$n / 1000" | bc -l)" \
        --pose "0,0.05,3,0.1,0,0.04,2,0.7,0.5,0.03,4,0.3,0,0.10,2.5,1.1,0,0.08,3.5,0.4,0,0.15,1.5,0.9" \
        >/dev/null 2>&1 ;;
    *)
      valgrind --tool=callgrind --toggle-collect="$f" --callgrind-out-file="$file" \
        "$b/bench-calls" "$row" "$n" >/dev/null 2>&1 ;;
  esac
  local total
  total="$(awk '/^totals:/ {print $2}' "$file")"
  echo $((total / n))
}

# Median ns per call, natively.
median_ns() {  # build_dir row
  local b="$1" row="$2"
  case "$row" in
    fmu-dostep-*)
      local fidelity
      case "$row" in *kinematic) fidelity=0 ;; *massless) fidelity=1 ;; *) fidelity=2 ;; esac
      "$b/fmu_bench" "$b/fmu/StewartPlatform/fmi2/StewartPlatform.so" --fidelity "$fidelity" \
        --step 0.001 --duration "$(echo "$median_calls / 1000" | bc -l)" \
        --pose "0,0.05,3,0.1,0,0.04,2,0.7,0.5,0.03,4,0.3,0,0.10,2.5,1.1,0,0.08,3.5,0.4,0,0.15,1.5,0.9" \
        | sed -n 's/.*doStep_us_median=\([0-9.]*\).*/\1/p' | awk '{printf "%.1f", $1 * 1000}' ;;
    *) "$b/bench-calls" "$row" "$median_calls" | sed -n 's/.*median \([0-9.]*\) ns.*/\1/p' ;;
  esac
}

{
  echo "Issue 22 cost table: reference $commit ($(git -C "$ref" log -1 --format=%h)) vs this tree ($(git -C "$repo" log -1 --format=%h)$(git -C "$repo" diff --quiet HEAD || echo ', uncommitted changes'))"
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "instructions per call: callgrind, counted inside the function, $calls calls along the combined cue"
  echo "medians: $median_calls calls, native, same harness (FMU rows: tests/importer/fmu_bench)"
  echo
  printf '%-22s %-22s %12s %12s %8s %12s %12s %8s\n' row function "Ir ref" "Ir now" ratio \
    "ns ref" "ns now" ratio
  for row in "${ROWS[@]}"; do
    a="$(per_call "$ref/build" "$row")"; b="$(per_call "$repo/build" "$row")"
    ma="$(median_ns "$ref/build" "$row")"; mb="$(median_ns "$repo/build" "$row")"
    printf '%-22s %-22s %12s %12s %8.2f %12s %12s %8.2f\n' "$row" "${FUNCTION[$row]}" "$a" "$b" \
      "$(echo "$a / $b" | bc -l)" "$ma" "$mb" "$(echo "$ma / $mb" | bc -l)"
  done
  if ((benches)); then
    for prog in bench-closed-form bench-full bench-forward bench-plant; do
      for side in reference now; do
        b="$repo/build"; [ "$side" = reference ] && b="$ref/build"
        echo; echo "== $prog ($side) =="
        "$b/$prog" 2>&1 || echo "($prog failed)"
      done
    done
  fi
} | tee "$out"
echo "written: $out" >&2
