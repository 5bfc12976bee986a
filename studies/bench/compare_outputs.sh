#!/usr/bin/env bash
# Every CLI and FMU output of a reference build (studies/bench/reference.sh COMMIT) against this
# tree's build/, scene by scene (studies/bench/compare_outputs.py says what and how).
# usage: studies/bench/compare_outputs.sh [--commit C (171f04e)] [--bound B (1e-9)] [--keep DIR]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
commit=171f04e; extra=()
while (($#)); do
  case "$1" in
    --commit) commit="$2"; shift 2 ;;
    *) extra+=("$1"); shift ;;
  esac
done
ref="$(bash "$repo/studies/bench/reference.sh" "$commit")"
nice -n 10 cmake --build "$repo/build" -j2 --target stewart-solve stewart-simulate \
  StewartPlatform_fmu2 StewartPlatform_fmu3 StewartPlant_fmu2 StewartPlant_fmu3 >&2
# The venv's installed package (PYTHONPATH=python, the source tree, has no built extension).
env -u PYTHONPATH "$repo/.venv/bin/python" "$repo/studies/bench/compare_outputs.py" "$ref/build" "$repo/build" \
  "${extra[@]+"${extra[@]}"}"
