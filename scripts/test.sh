#!/usr/bin/env bash
# The test command: set up, build, then run every test: Unity and the C checks through ctest, the
# same under AddressSanitizer + UndefinedBehaviorSanitizer, the thread tests under
# ThreadSanitizer, both FMUs through fmpy under valgrind, then pytest. The gates live with the
# tests (tests/gates/). Each step says how long it took (the whole command should stay well under
# 30 minutes on a 2-core machine).
set -euo pipefail
cd "$(dirname "$0")/.."
step() {
  local name=$1 start=$SECONDS
  shift
  "$@"
  echo "test.sh: $name took $((SECONDS - start)) s"
}
step "setup and build" bash scripts/build.sh
step "ctest" bash -c 'cd build && ctest -j"$(nproc)" --output-on-failure'
step "the ASan + UBSan gate" bash tests/gates/sanitize.sh
step "the TSan gate" bash tests/gates/tsan.sh
step "the valgrind gate" bash tests/gates/valgrind_fmu.sh build
STEWART_BUILD_DIR="$PWD/build" .venv/bin/python -m pytest tests/python -q
