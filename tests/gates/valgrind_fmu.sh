#!/usr/bin/env bash
# Runs short fmpy simulations of both FMUs (FMI 2.0 and 3.0; fidelities 0 and 1, and 2 when the
# build solves it) under valgrind memcheck, plus the unit's edge paths (a non-finite input, a
# singular pose, an invalid step, FMU state get/set/serialise, reset), and fails on any error whose
# stack touches StewartPlatform.so (or StewartPlant.so: the plant's forced motion and edges): invalid reads or writes, uses of uninitialised values, invalid
# frees, and definitely lost blocks allocated from it.
#
# Python and numpy have their own valgrind noise (the interpreter's arenas, interned objects kept
# until exit): valgrind runs with --error-exitcode=1 --errors-for-leak-kinds=definite and writes XML,
# and the verdict counts only the errors with a frame in StewartPlatform.so (PYTHONMALLOC=malloc so
# that every Python allocation is visible to valgrind too). The process valgrind watches is
# tests/gates/valgrind_drive.py; tests/gates/valgrind_verdict.py reads its XML report.
# usage: tests/gates/valgrind_fmu.sh [BUILD_DIR=build]   (takes about 20 s)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(realpath "${1:-build}")
python=.venv/bin/python
[ -x "$python" ] || { echo "valgrind_fmu: run scripts/build.sh first (no .venv)"; exit 2; }
for f in "$build"/fmus/{2.0,3.0}/{StewartPlatform,StewartPlant}.fmu; do
  [ -f "$f" ] || { echo "valgrind_fmu: $f is missing: build first"; exit 2; }
done
if ! command -v valgrind >/dev/null; then
  as_root=""; [ "$(id -u)" -eq 0 ] || as_root="sudo"
  DEBIAN_FRONTEND=noninteractive $as_root apt-get install -y -qq --no-install-recommends valgrind >/dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

start=$(date +%s)
set +e
PYTHONMALLOC=malloc valgrind --tool=memcheck --error-exitcode=1 --errors-for-leak-kinds=definite \
  --leak-check=full --show-leak-kinds=definite --track-origins=yes --num-callers=40 \
  --keep-debuginfo=yes \
  --xml=yes --xml-file="$work/memcheck.xml" \
  "$python" tests/gates/valgrind_drive.py "$build" >"$work/out.txt" 2>&1
rc=$?
set -e
grep '^valgrind_fmu:' "$work/out.txt" || true
if ! grep -q 'DRIVER DONE' "$work/out.txt"; then
  tail -30 "$work/out.txt"
  echo "valgrind_fmu: the simulations did not complete (exit $rc)"
  exit 1
fi

"$python" tests/gates/valgrind_verdict.py "$work/memcheck.xml"
echo "valgrind_fmu: clean ($(($(date +%s) - start)) s)"
