#!/usr/bin/env bash
# The test command: set up, build, then run every test: Unity and the C checks through ctest, the
# same under AddressSanitizer + UndefinedBehaviorSanitizer, both FMUs through fmpy under valgrind,
# then pytest. The gates live with the tests (tests/gates/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
(cd build && ctest --output-on-failure)
bash tests/gates/sanitize.sh
bash tests/gates/tsan.sh
bash tests/gates/valgrind_fmu.sh build
STEWART_BUILD_DIR="$PWD/build" .venv/bin/python -m pytest tests/python -q
