#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the default study (the embedded
# cases/ead2002.toml) at the quick resolution into ./study/, ending with study/study_report.md and the
# plots. By default only case A_smooth (SPH and OpenFOAM); extra arguments go to
# `hydrojump study`, e.g. --cases A,B,C, or --cases all for all ten cases.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
"$here/scripts/setup.sh" "$build_dir"
cd "$here"
args=("$@")
has_cases=0
for a in "${args[@]}"; do
  case "$a" in --cases|--cases=*) has_cases=1 ;; esac
done
if [ "$has_cases" -eq 0 ]; then args+=(--cases A_smooth); fi
# "--cases all" means every case: drop the option.
filtered=()
skip=0
for a in "${args[@]}"; do
  if [ "$skip" -eq 1 ]; then skip=0; [ "$a" = all ] && { unset 'filtered[-1]'; continue; }; fi
  [ "$a" = --cases ] && skip=1
  [ "$a" = --cases=all ] && continue
  filtered+=("$a")
done
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
exec "$build_dir/compare/hydrojump" study default --resolution quick --out study "${filtered[@]}"
