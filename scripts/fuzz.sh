#!/usr/bin/env bash
# Fuzzes the C API (tests/fuzz/fuzz_api.cpp) and the FMU's FMI 2 set/step/get sequence
# (tests/fuzz/fuzz_fmu.cpp) with libFuzzer (clang from Debian) for a bounded time each, with
# AddressSanitizer (FUZZ_SANITIZERS=address,undefined adds UBSan, at a quarter of the speed:
# docs/limits.md 5.4; the test command replays every corpus under ASan + UBSan anyway), and merges
# what they find into tests/fuzz/corpus/api and tests/fuzz/corpus/fmu (which the test suite
# replays).
# With `minimize` instead of a target, it fuzzes nothing and shrinks both corpora to the inputs that
# add edge coverage (libFuzzer -merge=1 into an empty folder, -use_counters=0: the hit-count buckets
# a campaign also tells apart would keep about ten times as many inputs for the same edges).
# The plant FMU (tests/fuzz/fuzz_plant_fmu.cpp, corpus tests/fuzz/corpus/plant_fmu): target `plant`;
# the Model Exchange plant (tests/fuzz/fuzz_plant_me_fmu.cpp, corpus tests/fuzz/corpus/plant_me_fmu):
# target `me`. The platform-file reader (tests/fuzz/fuzz_platform_file.cpp, corpus
# tests/fuzz/corpus/platform_file): target `platform`.
# Environment: FUZZ_RUNS=N stops each target after N inputs (SECONDS stays the cap; docs/limits.md
# 5.4 has the campaigns' rates); FUZZ_MAX_LEN (default 4096) caps an input's bytes: libFuzzer lets
# inputs grow, and the per-input work (operations, steps) with them, so the rate falls as a
# campaign goes on.
# usage: scripts/fuzz.sh [SECONDS=60 per target] [api|fmu|plant|me|platform|all=all five]
#        scripts/fuzz.sh 0 minimize
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
targets=${2:-both}
bash scripts/setup.sh
# libomp: SUNDIALS's CMake package asks for OpenMP, which clang finds only with it.
for p in clang libclang-rt-14-dev libomp-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="${missing:-} $p"
done
if [ -n "${missing:-}" ]; then
  as_root=""; [ "$(id -u)" -eq 0 ] || as_root="sudo"
  DEBIAN_FRONTEND=noninteractive $as_root apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
flags="-fsanitize=fuzzer-no-link,${FUZZ_SANITIZERS:-address} -fno-sanitize-recover=all -g"
# Both targets are built by CMake (tests/CMakeLists.txt, STEWART_FUZZ): the library and the FMU's
# objects are compiled once, with the sanitizer flags, exactly as the replay tests use them.
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DSTEWART_FUZZ=ON \
  -DPython3_EXECUTABLE="$PWD/.venv/bin/python" -DUNITY_WHEEL_DIR="$PWD/.cache/wheels" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_api fuzz_fmu fuzz_plant_fmu fuzz_plant_me_fmu \
  fuzz_platform_file

# run TARGET CORPUS: fuzz for $seconds from the committed corpus, then keep only the inputs that
# add edge coverage to it. Prints the number of executions.
run() {
  local target=$1 corpus=$2
  mkdir -p build-fuzz/corpus_$target "$corpus"
  ./build-fuzz/$target -max_total_time="$seconds" -runs="${FUZZ_RUNS:--1}" \
    -max_len="${FUZZ_MAX_LEN:-4096}" -artifact_prefix=build-fuzz/$target- \
    -print_final_stats=1 build-fuzz/corpus_$target "$corpus" 2>build-fuzz/$target.log || {
    tail -50 build-fuzz/$target.log; echo "fuzz: $target FAILED (artifact in build-fuzz/)"; exit 1; }
  ./build-fuzz/$target -merge=1 -use_counters=0 "$corpus" build-fuzz/corpus_$target 2>>build-fuzz/$target.log
  echo "fuzz: $target $(grep -m1 stat::number_of_executed_units build-fuzz/$target.log | awk '{print $2}') executions in ${seconds} s; corpus now $(ls "$corpus" | wc -l) inputs ($(du -sh "$corpus" | cut -f1))"
}
# minimize TARGET CORPUS: keep only the inputs of CORPUS that add coverage, in place.
minimize() {
  local target=$1 corpus=$2 kept=build-fuzz/minimized_$1
  local before="$(ls "$corpus" | wc -l) inputs ($(du -sh "$corpus" | cut -f1))"
  rm -rf "$kept"; mkdir -p "$kept"
  ./build-fuzz/$target -merge=1 -use_counters=0 "$kept" "$corpus" 2>build-fuzz/$target-minimize.log || {
    tail -20 build-fuzz/$target-minimize.log; echo "fuzz: minimising $corpus FAILED"; exit 1; }
  rm -f "$corpus"/*
  cp "$kept"/* "$corpus"/
  echo "fuzz: $corpus minimised from $before to $(ls "$corpus" | wc -l) inputs ($(du -sh "$corpus" | cut -f1))"
}
case "$targets" in
  minimize) minimize fuzz_api tests/fuzz/corpus/api; minimize fuzz_fmu tests/fuzz/corpus/fmu
    minimize fuzz_plant_fmu tests/fuzz/corpus/plant_fmu
    minimize fuzz_plant_me_fmu tests/fuzz/corpus/plant_me_fmu
    minimize fuzz_platform_file tests/fuzz/corpus/platform_file ;;
  api) run fuzz_api tests/fuzz/corpus/api ;;
  fmu) run fuzz_fmu tests/fuzz/corpus/fmu ;;
  plant) run fuzz_plant_fmu tests/fuzz/corpus/plant_fmu ;;
  me) run fuzz_plant_me_fmu tests/fuzz/corpus/plant_me_fmu ;;
  platform) run fuzz_platform_file tests/fuzz/corpus/platform_file ;;
  *) run fuzz_api tests/fuzz/corpus/api; run fuzz_fmu tests/fuzz/corpus/fmu
    run fuzz_plant_fmu tests/fuzz/corpus/plant_fmu; run fuzz_plant_me_fmu tests/fuzz/corpus/plant_me_fmu
    run fuzz_platform_file tests/fuzz/corpus/platform_file ;;
esac
