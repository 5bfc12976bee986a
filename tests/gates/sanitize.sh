#!/usr/bin/env bash
# A test gate (scripts/test.sh runs it): builds the tests with AddressSanitizer +
# UndefinedBehaviorSanitizer into build-asan and runs them (and the fuzz corpus replay) there: any
# report fails the run.
# -O1, as ASan's authors advise: the same reports, and the sanitizer build compiles about three
# times faster than at -O2 (csrc/linearize/plant_dual.cpp alone 310 s -> 103 s on this machine).
# The benchmark programs are left out (STEWART_BUILD_BENCHMARKS=OFF), and so is ctest's core_only,
# which builds the core on its own without the sanitizers and so checks here exactly what it
# checks in the Release build.
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTEWART_SANITIZE=ON \
  -DSTEWART_BUILD_BENCHMARKS=OFF \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" \
  -DPython3_EXECUTABLE="$PWD/.venv/bin/python" -DUNITY_WHEEL_DIR="$PWD/.cache/wheels" >/dev/null
cmake --build build-asan -j"$(nproc)"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest -j"$(nproc)" --output-on-failure -E '^core_only$')
