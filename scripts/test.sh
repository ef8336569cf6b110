#!/usr/bin/env bash
# Installs what is missing, builds, and runs the test suite (everything not tagged [slow]).
# The long validation runs have their own command: scripts/validate.sh
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
"$here/scripts/setup.sh" "$build_dir"
cd "$build_dir"
ctest -LE slow --output-on-failure --timeout 900 -j 1
