#!/usr/bin/env bash
# Installs what is needed, builds build/meridian and runs the main job on the
# bundled example data (a gyro-theodolite station campaign).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMERIDIAN_BUILD_TESTS=OFF -DMERIDIAN_HTML_REPORTS=ON
cmake --build build -j"$(nproc)" --target meridian
./build/meridian demo
