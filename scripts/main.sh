#!/usr/bin/env bash
# The main job: set up, build, and run the default scene — the thesis' yaw manoeuvre (±10° at
# 5 rad/s for 12 s) at full fidelity through the FMI 2.0 FMU with fmpy — writing out/yaw.csv (every
# output), out/yaw.png (lengths, rates, forces per leg) and out/yaw_fidelity.png (forces of the
# massless and full models on one chart).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
.venv/bin/python scripts/run_scene.py yaw --fidelity 2 --derivatives 1 --compare 1,2 --out out
