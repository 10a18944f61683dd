#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang-14, in ./build-fuzz) and runs each for SECONDS, one after
# the other, niced, one fuzzing process at a time (fuzz/README.md).
#   scripts/fuzz.sh SECONDS [HARNESS...]     e.g. scripts/fuzz.sh 120 nrrd ply
# New corpus entries go to build-fuzz/fuzz/corpus/<harness> (the checked-in seeds in
# fuzz/corpus/<harness> are only read), crashing inputs to build-fuzz/fuzz/artifacts/<harness>/,
# logs to build-fuzz/fuzz/logs/, and one summary line per harness (executions, libFuzzer's final
# cov: and ft:, the outcome) to stdout and build-fuzz/fuzz/summary.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 1 ] || ! [[ $1 =~ ^[0-9]+$ ]]; then
  echo "usage: scripts/fuzz.sh SECONDS [HARNESS...]  (harnesses: $(ls fuzz/corpus | tr '\n' ' '))" >&2
  exit 2
fi
seconds=$1
shift
build=${FUZZ_BUILD_DIR:-build-fuzz}
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=${CC:-clang-14} CXX=${CXX:-clang++-14} cmake -S . -B "$build" -DISOCURV_FUZZ=ON \
    -DISOCURV_BUILD_TESTS=OFF -DISOCURV_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    ${CMAKE_ARGS:-} >/dev/null
fi
nice cmake --build "$build" --target fuzzers -j2 2>&1 | { grep -v -e '^\[' || true; }

harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || mapfile -t harnesses < <(ls fuzz/corpus)
out="$build/fuzz"
mkdir -p "$out/logs"
# Leaks are not reported: VTK, OpenVDB and TBB keep process-wide objects to the end.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
status=0
for h in "${harnesses[@]}"; do
  exe="$out/fuzz_$h"
  [ -x "$exe" ] || { echo "scripts/fuzz.sh: no harness '$h'" >&2; exit 2; }
  mkdir -p "$out/corpus/$h" "$out/artifacts/$h"
  log="$out/logs/$h.log"
  set +e
  # -malloc_limit_mb: any single allocation over 512 MiB is reported as a crash (inputs are a
  # few KiB, so that is a size taken from a header without checking it against the data). VTK's
  # XML reader allocated from compressed-block headers until read_vtp checked them first; vtp
  # keeps a 4 GiB limit. The vdb harness had one too, and ran in fork mode past OpenVDB's
  # allocations, until load_vdb walked the whole file first (fuzz/README.md).
  limit=512
  [ "$h" = vtp ] && limit=4200
  nice -n 19 "$exe" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -malloc_limit_mb=$limit \
    -max_len=24576 -print_final_stats=1 -artifact_prefix="$out/artifacts/$h/" \
    "$out/corpus/$h" "fuzz/corpus/$h" >"$log" 2>&1
  rc=$?
  set -e
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  execs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$log" | grep -oE '[0-9]+$' ||
          echo "$last" | grep -oE '^#[0-9]+' | tr -d '#' || echo "?")  # else its last status line's count
  cov=$(echo "$last" | grep -oE 'cov: [0-9]+' | grep -oE '[0-9]+' || echo "?")
  ft=$(echo "$last" | grep -oE 'ft: [0-9]+' | grep -oE '[0-9]+' || echo "?")
  if [ $rc -eq 0 ]; then outcome=ok; else outcome="FOUND (exit $rc): $(ls -t "$out/artifacts/$h" | head -1)"; status=1; fi
  line="$(date -u +%H:%M) $h ${seconds}s execs=$execs cov=$cov ft=$ft $outcome"
  echo "$line" | tee -a "$out/summary.txt"
done
exit $status
