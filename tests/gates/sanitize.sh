#!/usr/bin/env bash
# A test gate (scripts/test.sh runs it): builds everything with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan and runs
# the Unity tests (and the fuzz corpus replay) there: any report fails the run.
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTEWART_SANITIZE=ON \
  -DPython3_EXECUTABLE="$PWD/.venv/bin/python" -DUNITY_WHEEL_DIR="$PWD/.cache/wheels" >/dev/null
cmake --build build-asan -j"$(nproc)"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure)
