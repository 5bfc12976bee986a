#!/usr/bin/env bash
# Every CLI output bit for bit the same as a baseline build's (a refactoring changes no number):
# stewart-solve at every fidelity, with and without the scene's derivatives, stewart-solve
# --forward on the lengths it wrote (with and without rates), and stewart-simulate on its
# forces, for every Stewart scene in scenes/.
# usage: tests/gates/same_outputs.sh BASELINE_BUILD_DIR [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
baseline=${1:?usage: same_outputs.sh BASELINE_BUILD_DIR [BUILD_DIR]}
build=${2:-build}
python=${PYTHON:-.venv/bin/python}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
compare() {  # name, then the command with @BIN@ for the build's directory
  local name=$1; shift
  local ours=("${@//@BIN@/$build}") theirs=("${@//@BIN@/$baseline}")
  local ours_out="$work/$name.ours.csv" theirs_out="$work/$name.base.csv"
  "${ours[@]/@OUT@/$ours_out}" >"$work/$name.ours.log" 2>&1 || echo "exit $?" >>"$work/$name.ours.log"
  "${theirs[@]/@OUT@/$theirs_out}" >"$work/$name.base.log" 2>&1 || echo "exit $?" >>"$work/$name.base.log"
  local same_files=0
  if [ ! -e "$ours_out" ] && [ ! -e "$theirs_out" ]; then same_files=1  # both refused the run
  elif cmp -s "$ours_out" "$theirs_out"; then same_files=1; fi
  if [ $same_files = 1 ] && cmp -s "$work/$name.ours.log" "$work/$name.base.log"; then
    echo "same: $name"
  else
    echo "DIFFERENT: $name"; failed=1
  fi
}
for scene in scenes/*.json; do
  name=$(basename "$scene" .json)
  grep -q '"mechanism"' "$scene" && continue  # the slider-crank: not the platform
  "$python" scripts/scenes.py "$scene" "$work/$name.in.csv"
  "$python" scripts/scenes.py "$scene" "$work/$name.fd.csv" --no-derivatives
  for fidelity in kinematic massless full; do
    compare "$name.$fidelity" @BIN@/stewart-solve --fidelity $fidelity "$work/$name.in.csv" @OUT@
    compare "$name.$fidelity.fd" @BIN@/stewart-solve --fidelity $fidelity "$work/$name.fd.csv" @OUT@
  done
  # forward kinematics of the full level's lengths: with rates and accelerations, and lengths only
  "$build/stewart-solve" --fidelity full "$work/$name.in.csv" "$work/$name.legs.csv"
  cut -d, -f1-7 "$work/$name.legs.csv" >"$work/$name.lengths.csv"
  compare "$name.forward" @BIN@/stewart-solve --forward "$work/$name.legs.csv" @OUT@
  compare "$name.forward.lengths" @BIN@/stewart-solve --forward "$work/$name.lengths.csv" @OUT@
  # the plant driven by the full level's forces
  "$python" - "$work/$name.legs.csv" "$work/$name.forces.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w") as f:
    f.write("t," + ",".join(f"F{k}" for k in range(1, 7)) + "\n")
    for r in rows[:2001]:
        f.write(r["t"] + "," + ",".join(r[f"F{k}"] for k in range(1, 7)) + "\n")
PY
  for fidelity in massless full; do
    compare "$name.simulate.$fidelity" @BIN@/stewart-simulate --fidelity $fidelity \
      "$work/$name.forces.csv" @OUT@
  done
done
exit $failed
