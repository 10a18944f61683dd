#!/usr/bin/env bash
# Configures (once) and builds isocurv in ./build with 2 jobs, reusing the build directory.
#   scripts/build.sh                     everything the tests need (the default target, `all`)
#   scripts/build.sh isocurv TARGET...   only those targets and what they depend on
#                                        (scripts/demo.sh: the executable and the bundled datasets;
#                                        `benchmarks`: every benchmark)
# A new build folder uses Ninja where it is installed (scripts/setup.sh installs it), else Make.
# Progress: one line per tenth of the build (updated in place on a terminal), with the steps done
# and the time so far; warnings and errors are shown as the compiler prints them.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
say() { echo "isocurv build: $*" >&2; }
start=$(date +%s)
took() { local t=$(( $(date +%s) - start )); printf '%dm%02ds' $((t / 60)) $((t % 60)); }
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  say "configuring $BUILD_DIR (Release${generator[1]:+, ${generator[1]}})"
  # (Debian's FindOpenVDB.cmake prints "COMPONENT = openvdb": not ours, left out.)
  cmake -S . -B "$BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release ${CMAKE_ARGS:-} \
    2> >(grep -v '^COMPONENT = ' >&2) >/dev/null
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
say "building ${*:-everything} in $BUILD_DIR with 2 jobs"
# Ninja prints "[done/total] ...", Make "[ NN%] ...": both become a percentage, shown at each
# tenth; every other line (warnings, errors, the generators' own messages) passes through.
export NINJA_STATUS="[%f/%t] "
awk_line=(awk)  # mawk (Debian's awk) reads a pipe in blocks unless told otherwise
awk -W version 2>&1 | grep -q mawk && awk_line=(awk -W interactive)
set +e
cmake --build "$BUILD_DIR" -j2 "${targets[@]}" 2>&1 | "${awk_line[@]}" -v start="$start" -v tty="$([ -t 2 ] && echo 1 || echo 0)" '
  function show(pct, steps,   el) {
    el = systime() - start
    line = sprintf("isocurv build: %3d%%%s, %dm%02ds", pct, steps, el / 60, el % 60)
    if (tty) { printf "\r%s", line > "/dev/stderr"; shown_inline = 1 }
    else print line > "/dev/stderr"
  }
  /^\[[0-9]+\/[0-9]+\] / {
    if ($0 ~ /Re-running CMake|Re-checking globbed/) next
    split(substr($1, 2, length($1) - 2), f, "/")
    pct = int(100 * f[1] / f[2])
    if (pct >= next_pct || f[1] == f[2]) { show(pct, sprintf(" (%d/%d steps)", f[1], f[2])); next_pct = (int(pct / 10) + 1) * 10 }
    next
  }
  /^\[ *[0-9]+%\] / {
    pct = substr($0, 2, 3) + 0
    if (pct >= next_pct) { show(pct, ""); next_pct = (int(pct / 10) + 1) * 10 }
    next
  }
  /^Consolidate compiler|^ninja: no work to do|Re-running CMake/ { next }
  { if (shown_inline) { printf "\n" > "/dev/stderr"; shown_inline = 0 } print }
  END { if (shown_inline) printf "\n" > "/dev/stderr" }'
status=${PIPESTATUS[0]}
set -e
if [ "$status" -ne 0 ]; then
  say "FAILED after $(took) (the compiler's message is above)"
  exit "$status"
fi
say "done in $(took)"
