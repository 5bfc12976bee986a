#!/usr/bin/env bash
# Sets up (scripts/setup.sh), then configures and builds everything into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$PWD/.venv/bin/python" \
  -DUNITY_WHEEL_DIR="$PWD/.cache/wheels" >/dev/null
cmake --build build -j"$(nproc)"
