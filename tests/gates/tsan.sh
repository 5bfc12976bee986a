#!/usr/bin/env bash
# A test gate (scripts/test.sh runs it): builds the thread tests (tests/unit/test_threads.c: eight
# jobs on one shared model and eight FMU instances, sequential then in threads, bit for bit) with
# ThreadSanitizer into build-tsan, and runs it, and the threads of tests/unit/test_plant_fmu.c: any
# TSan report fails the run (halt_on_error).
# Only the test and what it links are built (the library, the FMU's static model and FMI 2
# layer); SUNDIALS comes from Debian and is not instrumented (docs/limits.md). STEPS (default 1000)
# are the communication steps per job: TSan runs the test ~10x slower than a Release build.
set -euo pipefail
cd "$(dirname "$0")/../.."
steps="${1:-1000}"
tsan_flags="-fsanitize=thread -fno-omit-frame-pointer -g1"
# -O1 and line tables (-g1), as the ASan gate: a report names file and line; the build is faster.
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" \
  -DCMAKE_C_FLAGS="$tsan_flags" -DCMAKE_CXX_FLAGS="$tsan_flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
  -DPython3_EXECUTABLE="$PWD/.venv/bin/python" -DUNITY_WHEEL_DIR="$PWD/.cache/wheels" >/dev/null
cmake --build build-tsan -j"$(nproc)" --target test_threads test_plant_fmu
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" build-tsan/tests/test_threads "$steps"
# The plant FMU: four instances (FMI 2 and 3, both fidelities) in threads against sequential runs.
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" build-tsan/tests/test_plant_fmu "$steps" --threads-only
