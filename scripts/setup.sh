#!/usr/bin/env bash
# Installs what Meridian needs to build, test and run on Debian 12: the
# Debian packages below (as root, or with sudo) and the pinned JavaScript
# for HTML reports (web/package-lock.json, `npm ci` into web/node_modules).
# Does nothing that is already done.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(
  build-essential cmake pkg-config python3 python3-numpy python3-pywt
  libeigen3-dev libgeographiclib-dev geographiclib-tools
  libcli11-dev nlohmann-json3-dev libyaml-cpp-dev libfmt-dev libboost-math-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # Grid synthesis (FFTW) and grid files (netCDF C library; ncdump for the tests; PROJ's cct
  # reads the .gtx geoid grids back in the tests).
  libfftw3-dev libnetcdf-dev netcdf-bin proj-bin
  # GIS readers of the grids in the tests: GDAL (what QGIS uses) and GMT read each NetCDF grid's
  # extent, pixel size and CRS back (tests/cli/test_cli_gravity_grid.cpp).
  gdal-bin gmt
  # Unicode normalisation (NFKC) of point names: a full-width "Ⅱ３" is "Ⅱ3" (core/unicode.hpp).
  libutf8proc-dev
  # The Python package (MERIDIAN_PYTHON=ON, docs/python.md) and its tests.
  python3-dev python3-venv python3-pip-whl pybind11-dev python3-pybind11 python3-pytest python3-yaml python3-dask python3-distributed
  python3-netcdf4
  chromium fonts-dejavu-core fonts-liberation fonts-noto-cjk
  # libFuzzer harnesses (scripts/fuzz.sh): clang and its fuzzer/sanitizer runtimes.
  clang libclang-rt-14-dev
)
# Node.js and npm only fetch the report JavaScript; any installed node will do.
command -v npm > /dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The report JavaScript, exactly as pinned in the lockfile.
stamp=web/node_modules/.meridian-lock
if ! cmp -s web/package-lock.json "$stamp" 2> /dev/null; then
  echo "setup: npm ci in web/ (vega, vega-lite, vega-embed; yaml for the field book)"
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
  cp web/package-lock.json "$stamp"
fi
