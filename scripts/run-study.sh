#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the built-in study (the embedded
# cases/ead2002.toml) at the quick resolution into ./study/, ending with study/study_report.md and the
# plots. By default its run A and A's smooth twin (SPH and OpenFOAM: what the corrugated bed does to
# the jump); a study file given first runs all its cases unless --cases says otherwise. Arguments go to `hydrojump study`:
#   bash scripts/run-study.sh --cases A,B,C           # three cases (--cases all: all ten, many hours)
#   bash scripts/run-study.sh my_study.toml --resolution default --out runs/my_study
# A first argument that is not an option is the study file; --resolution and --out replace the
# defaults (quick, ./study).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
"$here/scripts/setup.sh" "$build_dir"
cd "$here"
spec=default
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then spec="$1"; shift; fi
has_cases=0 has_resolution=0 has_out=0
filtered=()
for a in "$@"; do
  case "$a" in
    --cases|--cases=*) has_cases=1 ;;  # "--cases all": every case (hydrojump study reads "all")
    --resolution|--resolution=*|-r) has_resolution=1 ;;
    --out|--out=*|-o) has_out=1 ;;
  esac
  filtered+=("$a")
done
# The built-in study runs A and A_smooth unless told otherwise; a study file of the user's runs all its cases.
[ "$has_cases" -eq 1 ] || [ "$spec" != default ] || filtered+=(--cases A,A_smooth)
[ "$has_resolution" -eq 1 ] || filtered+=(--resolution quick)
[ "$has_out" -eq 1 ] || filtered+=(--out study)
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
exec "$build_dir/hydrojump" study "$spec" "${filtered[@]}"
