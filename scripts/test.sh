#!/usr/bin/env bash
# Installs what is needed, builds everything with -Werror and runs the whole
# test suite: unit, CLI and validation tests (with the Python package's pytest
# suite, ctest label python), the find_package(Meridian) consumer check and
# `import meridian` from the installed package, unless MERIDIAN_SKIP_SANITIZERS=1 the suite again under
# AddressSanitizer + UndefinedBehaviorSanitizer, and unless MERIDIAN_FUZZ=0 each
# libFuzzer harness for FUZZ_SECONDS (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

echo "== Release build and tests"
# MERIDIAN_PYTHON only here: the extension is not built (nor its tests run) under the sanitizers.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMERIDIAN_BUILD_TESTS=ON -DMERIDIAN_HTML_REPORTS=ON -DMERIDIAN_PYTHON=ON
cmake --build build -j"$jobs"
ctest --test-dir build -j"$jobs" --output-on-failure

echo "== Installed package: find_package(Meridian) from a downstream project"
rm -rf build/install build/consumer
cmake --install build --prefix build/install > /dev/null
cmake -S tests/package -B build/consumer -DCMAKE_PREFIX_PATH="$PWD/build/install"
cmake --build build/consumer -j"$jobs"
./build/consumer/meridian_consumer
# The installed Python package, with Debian's interpreter (python/CMakeLists.txt) and nothing
# of the build tree on the path.
(cd build/install && PYTHONPATH="$PWD/lib/python3/dist-packages" /usr/bin/python3 -c \
  'import meridian, meridian.gravity as g; print("import meridian:", g.synthetic_model(4, 1))')

echo "== The wheel: pip wheel . installed into a fresh venv of Debian's Python, the docs' tour run there"
# The backend (python/build_backend/meridian_wheel.py) reuses the Release tree above; nothing is
# fetched from an index. --system-site-packages: numpy, dask and pytest are Debian's.
rm -rf build/wheel build/venv
MERIDIAN_WHEEL_BUILD_DIR="$PWD/build" /usr/bin/python3 -m pip wheel . -w build/wheel --no-deps --no-index -q
/usr/bin/python3 -m venv --system-site-packages build/venv
build/venv/bin/pip install --no-index -q build/wheel/meridian-*.whl
(cd / && "$OLDPWD/build/venv/bin/python" -c 'import meridian, sys; f = meridian.__file__; print("wheel:", f); sys.exit(0 if "/build/venv/" in f else 1)')
MERIDIAN_SOURCE_DIR="$PWD" MERIDIAN_CLI="$PWD/build/meridian" PYTHONDONTWRITEBYTECODE=1 \
  build/venv/bin/python -m pytest -q -p no:cacheprovider tests/python/test_docs.py

if [ "${MERIDIAN_SKIP_SANITIZERS:-0}" != 1 ]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  # -g1: line tables are all a sanitizer report needs; full -g made this build about
  # 16 % slower per file (test_stochastic.cpp: 40.9 s against 34.2 s) and its objects twice
  # as large.
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DMERIDIAN_SANITIZE=ON -DMERIDIAN_BUILD_TESTS=ON -DMERIDIAN_MONTECARLO_TESTS=OFF -DMERIDIAN_HTML_REPORTS=ON
  cmake --build build-asan -j"$jobs"
  # -LE montecarlo (and MERIDIAN_MONTECARLO_TESTS=OFF, so their executables are not even
  # built here): the Monte Carlo validations (tests/gyro/test_montecarlo.cpp,
  # ~30 000 reductions) are statistics, not memory checks: they run in the
  # Release pass above (1.2 s) and would take about a minute of CPU here
  # (57 s measured), on code the unit tests already exercise.
  # -E MonteCarlo: the same for the Monte Carlo cases inside unit-test binaries
  # (VarianceComponents.MonteCarloSigmaMatchesScatter alone took 141 s here, 2.7 s in
  # Release); browser: headless Chromium rendering a report, not our memory.
  # DovScenario: the deflection-of-the-vertical spec scenarios (hours of 1-10 Hz data, 0.1-2.5 s
  # each in Release) took 30-160 s each here (measured 2026-12-01); DovProcess runs the same
  # workflow code on short lines under the sanitizers.
  # The statistical cases added with issues 32/33/36 (seed loops over whole lines; Release runs
  # them in 0.2-1.5 s each) took 21-169 s each here (fresh-clone CI 2026-12-08: the sanitizer pass
  # 698 s of 42 min): NavConsistency.NoFalseAlarmOnCleanLines 169 s, DovStops 88 s, NavCli's
  # divergence case 48 s, the shared-orientation Monte Carlo 39 s, NavConsistency's current 32 s,
  # DovWhiteness 21 s. The same code runs here through the other Nav*/Dov*/Cli tests.
  slow='^DovScenario\.|^NavConsistency\.(NoFalseAlarmOnCleanLines|CurrentOf1p1)|^DovStops\.TwentyMinuteStop|^DovWhiteness\.WhiteNoisePasses|^NavCli\.DivergenceCaseIsMarkedAndGuarded|^Orientations\.SharedKnownLineAndEta'
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan -j"$jobs" --output-on-failure -LE "montecarlo|browser" -E "MonteCarlo|$slow"
fi
if [ "${MERIDIAN_FUZZ:-1}" != 0 ]; then
  # Every reader's libFuzzer harness for a bounded time (docs/reliability.md): 11 harnesses
  # x 15 s plus the clang build (about 85 s with unity builds, 2026-12-02; fuzz_dov_binary
  # added since: 15 s more). The whole command with it, the Python package and the nav and
  # dov modules: 25 min 28 s on an idle 2-core machine (fresh clone of 605afdf, 2026-12-02),
  # close to the 30-minute budget: the next addition must pay for itself.
  echo "== libFuzzer harnesses (clang, ASan+UBSan), ${FUZZ_SECONDS:-15} s each"
  FUZZ_SECONDS=${FUZZ_SECONDS:-15} bash scripts/fuzz.sh
fi
echo "== all tests passed"
