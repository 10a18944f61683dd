#!/usr/bin/env bash
# Quick-start command 1: installs what is missing, builds, and runs the main job on the bundled
# default dataset. Extra arguments are passed to `isocurv run` (e.g. --iso 0.3).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Only what the demo runs: the executable and the bundled datasets (scripts/test.sh builds the rest).
bash scripts/build.sh isocurv isocurv_datasets_vdb
exec "${BUILD_DIR:-build}/app/isocurv" run "${BUILD_DIR:-build}/datasets/torus.vdb" -o out --color K "$@"
