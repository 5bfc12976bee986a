#!/usr/bin/env bash
# The inverse unit built with its outputs copied (FMU_INVERSE_COPY_OUTPUTS=1, the path of ABIs that
# do not lay stewart_inverse_output over the output variables, e.g. i386) against the usual builds
# that write them in place: every output of fmu_bench --out, bit for bit, at the three fidelities,
# both derivative modes, and with warnings on every step (warn_condition = 1.5: near singular at
# the massless and full levels; stroke_max[1] = 0.5: leg 1 outside its stroke part of the time)
# and limit outputs, along a cue that moves every coordinate: all of it through FMI 2; through
# FMI 3 (its own usual step, which reports the last successful time) the plain and warning runs.
# usage: compare_copied_outputs.sh FMU_BENCH IN_PLACE_FMI2.so IN_PLACE_FMI3.so COPIED.so
# (COPIED.so holds both FMI layers)
set -euo pipefail
bench="$1" in_place2="$2" in_place3="$3" copied="$4"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# the combined cue of studies/bench/fmu_dostep.sh: every coordinate moves
pose="0,0.05,3,0.1,0,0.04,2,0.7,0.5,0.03,4,0.3,0,0.10,2.5,1.1,0,0.08,3.5,0.4,0,0.15,1.5,0.9"
runs=0
for fmi in 2 3; do
  in_place="$in_place2" extras=("" "--set warn_condition=1.5" "--set stroke_max[1]=0.5"
                                 "--set limit_outputs=1")
  if [ "$fmi" = 3 ]; then in_place="$in_place3" extras=("" "--set warn_condition=1.5"); fi
  for fidelity in 0 1 2; do
    for derivatives in 0 1; do
      for extra in "${extras[@]}"; do
        # shellcheck disable=SC2086 # extra is a list of options
        "$bench" "$in_place" --fmi "$fmi" --fidelity "$fidelity" --derivatives "$derivatives" \
          --step 0.001 --duration 0.3 --pose "$pose" $extra --out "$work/in_place.csv" >/dev/null
        # shellcheck disable=SC2086
        "$bench" "$copied" --fmi "$fmi" --fidelity "$fidelity" --derivatives "$derivatives" \
          --step 0.001 --duration 0.3 --pose "$pose" $extra --out "$work/copied.csv" >/dev/null
        if ! cmp -s "$work/in_place.csv" "$work/copied.csv"; then
          echo "copied outputs differ: FMI $fmi, fidelity $fidelity, derivatives $derivatives," \
               "$extra" >&2
          diff "$work/in_place.csv" "$work/copied.csv" | head -5 >&2
          exit 1
        fi
        if [ "$(wc -l <"$work/in_place.csv")" -lt 300 ]; then
          echo "fmu_bench wrote too few rows: FMI $fmi, fidelity $fidelity," \
               "derivatives $derivatives" >&2
          exit 1
        fi
        runs=$((runs + 1))
      done
    done
  done
done
echo "copied and in-place outputs agree bit for bit in $runs runs (FMI 2 and 3)"
