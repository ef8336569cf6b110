#!/usr/bin/env bash
# Installs hydrojump's Debian dependencies (only those missing; safe to run again) and builds it.
# Usage: scripts/setup.sh [BUILD_DIR]      (default build directory: ./build)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-$here/build}"

packages=(build-essential cmake libeigen3-dev libvtk9-dev libtomlplusplus-dev libcli11-dev catch2
          openfoam openmpi-bin libopenmpi-dev python3 python3-matplotlib python3-numpy)
# shellcheck source=scripts/packages.sh
source "$here/scripts/packages.sh"
install_missing_packages "${packages[@]}"

echo "setup: building in $build_dir"
cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j "$(nproc)"
