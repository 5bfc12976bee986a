#!/usr/bin/env bash
# Every scene in scenes/ into out/: CSV and plots for each (and the combined cue's animation).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
for scene in scenes/*.json; do
  .venv/bin/python scripts/run_scene.py "$(basename "$scene" .json)" --out out
done
