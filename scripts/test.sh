#!/usr/bin/env bash
# The test command: set up, build, then run every test: Unity and the C checks through ctest, the
# same under AddressSanitizer + UndefinedBehaviorSanitizer, both FMUs through fmpy under valgrind,
# then pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
(cd build && ctest --output-on-failure)
bash scripts/sanitize.sh
bash scripts/valgrind_fmu.sh build
STEWART_BUILD_DIR="$PWD/build" .venv/bin/python -m pytest tests/python -q
