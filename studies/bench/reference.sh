#!/usr/bin/env bash
# Builds a reference tree of an older commit beside this one, for the before/after scripts
# (instructions.sh, compare_outputs.sh): a detached `git worktree` of COMMIT in
# .cache/reference-COMMIT, configured like scripts/build.sh (Release, this tree's .venv and Unity
# wheel), with only the targets those scripts run. Prints the reference tree's path.
# usage: [HARNESS_COMMIT=C] studies/bench/reference.sh [COMMIT]   (default 171f04e: main before
# issue 22)
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
commit="${1:-171f04e}"
ref="$repo/.cache/reference-$commit"
targets=(stewart-solve stewart-simulate bench-closed-form bench-full bench-forward bench-plant
         fmu_bench StewartPlatform_fmu2 StewartPlatform_fmu3 StewartPlant_fmu2 StewartPlant_fmu3)
if [ ! -e "$ref/.git" ]; then
  git -C "$repo" worktree add --detach "$ref" "$commit" >&2
fi
if [ ! -f "$ref/build/CMakeCache.txt" ]; then
  cmake -S "$ref" -B "$ref/build" -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE="$repo/.venv/bin/python" -DUNITY_WHEEL_DIR="$repo/.cache/wheels" >&2
fi
nice -n 10 cmake --build "$ref/build" -j2 --target "${targets[@]}" >&2
# The call harness: the reference's own if it has one, else this repository's from commit
# HARNESS_COMMIT compiled against the reference's headers and libraries: by default 1d83b80, the
# harness as written before issue 18's one grammar, which speaks the API of references older than
# it (a reference after the grammar has its own harness).
if grep -q bench-calls "$ref/csrc/CMakeLists.txt"; then
  nice -n 10 cmake --build "$ref/build" -j2 --target bench-calls >&2
else
  harness="$ref/build/harness"
  mkdir -p "$harness/bench"
  for f in bench_calls.cpp combined_cue.hpp; do
    git -C "$repo" show "${HARNESS_COMMIT:-1d83b80}:csrc/bench/$f" > "$harness/bench/$f"
  done
  nice -n 10 g++ -O2 -std=c++17 -I"$harness" -I"$ref/csrc/include" -I"$ref/csrc/core/include" \
    "$harness/bench/bench_calls.cpp" -o "$ref/build/bench-calls" \
    "$ref/build/csrc/libstewart.a" "$ref/build/csrc/core/libmbs.a" \
    -l:libsundials_arkode.a -l:libsundials_cvode.a -l:libsundials_kinsol.a \
    -l:libsundials_nvecserial.a -l:libsundials_sunlinsoldense.a -l:libsundials_sunmatrixdense.a \
    -l:libsundials_generic.a -lm >&2
fi
echo "$ref"
