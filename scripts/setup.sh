#!/usr/bin/env bash
# Installs the Debian 12 packages Meridian needs to build, test and run.
# Run as root (or with sudo). Does nothing when everything is present.
set -euo pipefail
packages=(
  build-essential cmake pkg-config python3
  libeigen3-dev libgeographiclib-dev geographiclib-tools
  libcli11-dev nlohmann-json3-dev libyaml-cpp-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
)
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
