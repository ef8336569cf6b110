#!/usr/bin/env bash
# The main job's argument handling (scripts/run-study.sh): what it passes to `hydrojump study`.
# Runs the script against a stand-in build directory whose hydrojump prints its arguments and a
# setup.sh that does nothing, so nothing is installed or built.
set -euo pipefail
source_dir="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/scripts" "$work/build"
cp "$source_dir/scripts/run-study.sh" "$work/scripts/"
printf '#!/usr/bin/env bash\nexit 0\n' > "$work/scripts/setup.sh"
printf '#!/usr/bin/env bash\necho "$*"\n' > "$work/build/hydrojump"
chmod +x "$work/scripts/setup.sh" "$work/build/hydrojump"

failures=0
expect() {  # expect "<arguments of run-study.sh>" "<arguments hydrojump must receive>"
  local got
  # shellcheck disable=SC2086
  got="$(bash "$work/scripts/run-study.sh" $1)"
  if [ "$got" != "$2" ]; then
    echo "run-study.sh $1"
    echo "  passed:   $got"
    echo "  expected: $2"
    failures=$((failures + 1))
  fi
}
expect "" "study default --cases A,A_smooth --resolution quick --out study"
expect "--cases all" "study default --cases all --resolution quick --out study"
expect "--cases=all --jobs 2" "study default --cases=all --jobs 2 --resolution quick --out study"
expect "--cases A,B" "study default --cases A,B --resolution quick --out study"
expect "--cases=B" "study default --cases=B --resolution quick --out study"
expect "my.toml --resolution default --out runs" "study my.toml --resolution default --out runs"
expect "my.toml --cases B" "study my.toml --cases B --resolution quick --out study"
expect "--out runs --cases all --np 2" "study default --out runs --cases all --np 2 --resolution quick"
expect "-r default --methods sph" "study default -r default --methods sph --cases A,A_smooth --out study"
if [ "$failures" -ne 0 ]; then
  echo "$failures case(s) failed"
  exit 1
fi
echo "run-study.sh passes its arguments as documented (9 cases)"
