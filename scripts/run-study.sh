#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the default study (the embedded
# cases/ead2002.toml) at the quick resolution, ending with the report and plots in ./study/.
# Extra arguments go to `hydrojump study` (e.g. --cases A,A_smooth --resolution default).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
"$here/scripts/setup.sh" "$build_dir"
hydrojump="$build_dir/compare/hydrojump"
cd "$here"
if "$hydrojump" study --help >/dev/null 2>&1; then
  exec "$hydrojump" study default --resolution quick --out study "$@"
fi
"$hydrojump" check default
"$hydrojump" generate default --resolution quick --out study
echo "run-study: generated the case directories in ./study/. Not built yet: 'hydrojump study' (running"
echo "both solvers, comparing and plotting); run the solvers by hand as README.md describes."
