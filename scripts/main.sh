#!/usr/bin/env bash
# The main job: install what is missing, build the boomdyn program (not the
# tests: scripts/test.sh builds those), run the main scene and write its plots.
#   scripts/main.sh [extra boomdyn/PETSc options]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh boomdyn
dir=${BOOMDYN_BUILD_DIR:-build}
scene=inputs/paper_extraction.yaml
mkdir -p out
"$dir/boomdyn" "$scene" -o out/main.h5 -boom_overwrite "$@"
/usr/bin/python3 postprocess/plot_run.py out/main.h5 -o out/main_plots
/usr/bin/python3 postprocess/plot_frequency.py out/main.h5 -o out/main_plots/frequency.png --paper
echo "main: results in out/main.h5, plots in out/main_plots/"
