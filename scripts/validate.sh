#!/usr/bin/env bash
# The long validation runs (Catch2 cases tagged [slow]): dam break at two resolutions, still water,
# Poiseuille flow, hydraulic jumps. Hours on 2 cores; logs go to the build directory's Testing/ folder.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
"$here/scripts/setup.sh" "$build_dir"
cd "$build_dir"
ctest -L slow --output-on-failure -j 1 "$@"
