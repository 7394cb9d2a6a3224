#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs sewerplan's build and test dependencies from Debian 12 packages.
# Idempotent: packages already present are skipped, and apt is not touched when nothing is missing.
# Usage: scripts/install-deps.sh   (as root, or with sudo available)
set -euo pipefail

packages=(
  cmake g++ ninja-build git
  libboost-graph-dev libeigen3-dev libompl-dev nlohmann-json3-dev libsimdjson-dev libpugixml-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev
  clang libclang-rt-14-dev clang-format
  help2man dpkg-dev python3
  pybind11-dev python3-dev python3-pytest
  libproj-dev libcairo2-dev libgdal-dev gdal-bin
  libcpp-httplib-dev pkg-config chromium
  mmdebstrap  # scripts/deb-clean-root.sh: the package on a clean Debian 12 root
)
# node and npm build and test the operator station's page (web/). Debian's nodejs and npm are
# installed only where no npm exists: a Node.js from elsewhere (such as NodeSource's, which bundles
# npm and conflicts with Debian's npm package) is used as it is.
if ! command -v npm > /dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
