#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz (clang, ASan+UBSan, in
# build-fuzz/) and runs each for a bounded time on a copy of its seed corpus.
#   scripts/fuzz.sh                   every harness for FUZZ_SECONDS (default 20) each
#   scripts/fuzz.sh fuzz_icgem ...    only these harnesses
#   FUZZ_RUNS=1000000 scripts/fuzz.sh bounded by executions instead of time
#   FUZZ_JOBS=1 scripts/fuzz.sh       one harness at a time (default: one per core)
# A crash, a leak, a hang (> 10 s on one input) or an allocation above
# FUZZ_RSS_MB (default 1024) stops with the reproducer written to
# build-fuzz/findings/<harness>/ and exit status 1. docs/reliability.md
# records the runs.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-20}
rss=${FUZZ_RSS_MB:-1024}
harnesses=(fuzz_gyro_reduce fuzz_gyro_campaign fuzz_icgem fuzz_egm fuzz_grid_gtx fuzz_grid_pgm fuzz_points_csv
  fuzz_dov_line fuzz_dov_binary fuzz_nmea fuzz_nav_csv)
(($#)) && harnesses=("$@")
command -v clang++ > /dev/null || { echo "fuzz.sh: clang++ is missing (scripts/setup.sh installs it)" >&2; exit 1; }
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  # -O1 with line tables (libFuzzer's advice), assertions on.
  CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_CXX_FLAGS_FUZZ="-O1 -gline-tables-only" \
    -DMERIDIAN_BUILD_FUZZERS=ON -DMERIDIAN_BUILD_TESTS=OFF -DMERIDIAN_HTML_REPORTS=OFF > /dev/null
fi
cmake --build build-fuzz -j"$(nproc)" --target fuzzers
# The harnesses write each input to a file (the readers take paths): in memory where possible.
scratch_base=/dev/shm; [ -d "$scratch_base" ] && [ -w "$scratch_base" ] || scratch_base=${TMPDIR:-/tmp}
MERIDIAN_FUZZ_SCRATCH=$(mktemp -d "$scratch_base/meridian-fuzz.XXXXXX")
export MERIDIAN_FUZZ_SCRATCH
trap 'rm -rf "$MERIDIAN_FUZZ_SCRATCH"' EXIT
# FUZZ_JOBS harnesses at a time (default: the number of cores): each libFuzzer process is
# single-threaded, so two cores run two harnesses in the wall time of one, each for its full time.
jobs=${FUZZ_JOBS:-$(nproc)}
run_one() {  # harness -> build-fuzz/<harness>.log and .status
  local h=$1 work=build-fuzz/corpus/$1 findings=build-fuzz/findings/$1
  mkdir -p "$work" "$findings"
  cp -n tests/fuzz/corpus/"$h"/* "$work"/ 2> /dev/null || true
  local limit=(-max_total_time="$seconds")
  [ -n "${FUZZ_RUNS:-}" ] && limit=(-runs="$FUZZ_RUNS")
  local rc=0
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    build-fuzz/tests/fuzz/"$h" "${limit[@]}" -max_len=16384 -timeout=10 -rss_limit_mb="$rss" \
      -malloc_limit_mb="$rss" -print_final_stats=1 -artifact_prefix="$findings/" "$work" \
      > "build-fuzz/$h.log" 2>&1 || rc=$?
  echo "$rc" > "build-fuzz/$h.status"
}
report_one() {  # prints a finished harness's summary; returns its status
  local h=$1
  echo "== $h (${FUZZ_RUNS:+$FUZZ_RUNS runs}${FUZZ_RUNS:-$seconds s})"
  if [ "$(cat "build-fuzz/$h.status")" != 0 ]; then
    tail -n 60 "build-fuzz/$h.log"
    echo "fuzz.sh: $h found a problem; reproducer in build-fuzz/findings/$h/" >&2
    return 1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "build-fuzz/$h.log" | tr '\n' ' '
  echo
}
status=0
for ((i = 0; i < ${#harnesses[@]}; i += jobs)); do
  batch=("${harnesses[@]:i:jobs}")
  for h in "${batch[@]}"; do run_one "$h" & done
  wait
  for h in "${batch[@]}"; do report_one "$h" || status=1; done
done
exit $status
