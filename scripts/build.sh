#!/usr/bin/env bash
# Configures (once) and builds isocurv in ./build with 2 jobs, reusing the build directory.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release ${CMAKE_ARGS:-} >/dev/null
fi
# Show warnings and errors, not the progress lines; the build's own status is the script's.
cmake --build "$BUILD_DIR" -j2 2>&1 | { grep -v -e '^\[' -e '^Consolidate compiler' || true; }
