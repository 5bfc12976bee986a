#!/usr/bin/env bash
# The main job: set up, build, and run the thesis' yaw manoeuvre (±10° at 5 rad/s for 12 s) at
# the massless-leg level, writing out/yaw_pose.csv (the input), out/yaw.csv and out/yaw.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
.venv/bin/python scripts/scenes.py yaw out/yaw_pose.csv --dt 0.1
build/stewart-solve --fidelity massless out/yaw_pose.csv out/yaw.csv
.venv/bin/python scripts/plot_legs.py out/yaw.csv out/yaw.png --title "Yaw ±10° at 5 rad/s, massless legs"
echo "main: wrote out/yaw.csv and out/yaw.png"
