#!/usr/bin/env bash
# Fuzzes the C API with libFuzzer (clang from Debian) for a bounded time, with AddressSanitizer
# and UndefinedBehaviorSanitizer, and merges what it finds into tests/fuzz/corpus/api (which the
# test suite replays). usage: scripts/fuzz.sh [SECONDS=60]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
bash scripts/setup.sh
# libomp: SUNDIALS's CMake package asks for OpenMP, which clang finds only with it.
for p in clang libclang-rt-14-dev libomp-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="${missing:-} $p"
done
if [ -n "${missing:-}" ]; then
  as_root=""; [ "$(id -u)" -eq 0 ] || as_root="sudo"
  DEBIAN_FRONTEND=noninteractive $as_root apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -g"
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DPython3_EXECUTABLE="$PWD/.venv/bin/python" -DUNITY_WHEEL_DIR="$PWD/.cache/wheels" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target stewart
clang++ -std=c++17 $flags -fsanitize=fuzzer -Icsrc/include tests/fuzz/fuzz_api.cpp \
  build-fuzz/csrc/libstewart.a -o build-fuzz/fuzz_api
mkdir -p build-fuzz/corpus
./build-fuzz/fuzz_api -max_total_time="$seconds" -max_len=4096 -artifact_prefix=build-fuzz/ \
  build-fuzz/corpus tests/fuzz/corpus/api
# Keep only inputs that add coverage to the committed corpus.
./build-fuzz/fuzz_api -merge=1 tests/fuzz/corpus/api build-fuzz/corpus
echo "fuzz: corpus now $(ls tests/fuzz/corpus/api | wc -l) inputs"
