#!/usr/bin/env bash
# Installs what is needed, builds everything with -Werror and runs the whole
# test suite: unit, CLI and validation tests, the find_package(Meridian)
# consumer check, unless MERIDIAN_SKIP_SANITIZERS=1 the suite again under
# AddressSanitizer + UndefinedBehaviorSanitizer, and unless MERIDIAN_SKIP_FUZZ=1
# each libFuzzer harness for FUZZ_SECONDS (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

echo "== Release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMERIDIAN_BUILD_TESTS=ON -DMERIDIAN_HTML_REPORTS=ON
cmake --build build -j"$jobs"
ctest --test-dir build -j"$jobs" --output-on-failure

echo "== Installed package: find_package(Meridian) from a downstream project"
rm -rf build/install build/consumer
cmake --install build --prefix build/install > /dev/null
cmake -S tests/package -B build/consumer -DCMAKE_PREFIX_PATH="$PWD/build/install"
cmake --build build/consumer -j"$jobs"
./build/consumer/meridian_consumer

if [ "${MERIDIAN_SKIP_SANITIZERS:-0}" != 1 ]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DMERIDIAN_SANITIZE=ON -DMERIDIAN_BUILD_TESTS=ON -DMERIDIAN_HTML_REPORTS=ON
  cmake --build build-asan -j"$jobs"
  # -LE montecarlo: the Monte Carlo validations (tests/gyro/test_montecarlo.cpp,
  # ~30 000 reductions) are statistics, not memory checks: they run in the
  # Release pass above (1.2 s) and would take about a minute of CPU here
  # (57 s measured), on code the unit tests already exercise.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan -j"$jobs" --output-on-failure -LE montecarlo
fi
if [ "${MERIDIAN_SKIP_FUZZ:-0}" != 1 ]; then
  # Every reader's libFuzzer harness for a bounded time (docs/reliability.md):
  # 7 harnesses x 15 s plus the clang build (about 4.5 CPU-minutes): about 4 minutes on 2 cores.
  echo "== libFuzzer harnesses (clang, ASan+UBSan), ${FUZZ_SECONDS:-15} s each"
  FUZZ_SECONDS=${FUZZ_SECONDS:-15} bash scripts/fuzz.sh
fi
echo "== all tests passed"
