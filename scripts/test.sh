#!/usr/bin/env bash
# Quick-start command 2: installs what is missing, builds, and runs the whole test suite (CTest).
#   scripts/test.sh --sanitize   the same with address and undefined-behaviour sanitizers
#                                (-DISOCURV_SANITIZE=ON, RelWithDebInfo) in ./build-sanitize; any
#                                sanitizer report fails its test. Leak checking is off: VTK,
#                                OpenVDB, TBB and PoCL keep process-wide allocations to the end.
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=0
for arg in "$@"; do
  case "$arg" in
    --sanitize) sanitize=1 ;;
    *) echo "usage: scripts/test.sh [--sanitize]" >&2; exit 2 ;;
  esac
done
bash scripts/setup.sh
if [ $sanitize = 1 ]; then
  export BUILD_DIR=${BUILD_DIR:-build-sanitize}
  export CMAKE_ARGS="${CMAKE_ARGS:-} -DISOCURV_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DISOCURV_BUILD_BENCH=OFF"
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
fi
bash scripts/build.sh
cd "${BUILD_DIR:-build}"
ctest --output-on-failure -j2 --timeout 900
