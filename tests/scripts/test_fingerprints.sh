#!/usr/bin/env bash
# The run caches' code fingerprints (cmake/write_version.cmake): documentation (*.md), spec files
# (*.toml) and data (*.csv) never change them; a comparator source changes source_fingerprint only;
# a solver source (committed, uncommitted or untracked) changes both. Runs the script on a small git
# repository made here. Arguments: the cmake executable, the project's source directory.
set -euo pipefail
cmake_exe="$1"
source_dir="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
repo="$work/repo"
mkdir -p "$repo"/{util,cases,sph,reference,compare,app,cmake}
cd "$repo"
git init -q
git config user.email test@example.com
git config user.name test
echo "int solver;" > sph/a.cpp
echo "# sph" > sph/README.md
echo "id = 1" > cases/study.toml
echo "x,y" > cases/data.csv
echo "int spec;" > cases/spec.cpp
echo "int writer;" > reference/w.cpp
echo "int gen;" > app/generate.cpp
echo "int gen_h;" > app/generate.hpp
echo "int study;" > app/study.cpp
echo "int util;" > util/u.cpp
echo "int cmp;" > compare/other.cpp
echo "# build" > cmake/x.cmake
echo "project(x)" > CMakeLists.txt
git add -A
git commit -qm initial

fingerprints() {  # prints "source solver"
  "$cmake_exe" -DSRC="$repo" -DVERSION=1.0 -DOUT="$work/version.hpp" -P "$source_dir/cmake/write_version.cmake" >/dev/null
  local src sol
  src="$(sed -n 's/.*source_fingerprint = "\(.*\)";/\1/p' "$work/version.hpp")"
  sol="$(sed -n 's/.*solver_fingerprint = "\(.*\)";/\1/p' "$work/version.hpp")"
  echo "$src $sol"
}
failures=0
expect() {  # expect WHAT "same|differs" "same|differs" (source, solver) against the previous state
  local now src0 sol0 src1 sol1
  now="$(fingerprints)"
  read -r src0 sol0 <<< "$before"
  read -r src1 sol1 <<< "$now"
  local got_src=same got_sol=same
  [ "$src0" = "$src1" ] || got_src=differs
  [ "$sol0" = "$sol1" ] || got_sol=differs
  if [ "$got_src" != "$2" ] || [ "$got_sol" != "$3" ]; then
    echo "$1: source fingerprint $got_src (expected $2), solver fingerprint $got_sol (expected $3)"
    failures=$((failures + 1))
  fi
  before="$now"
}
before="$(fingerprints)"
case "$before" in *+code.*" "*+code.*) ;; *) echo "fingerprints not computed: $before"; exit 1 ;; esac

echo "# more" >> sph/README.md;        expect "uncommitted *.md" same same
git commit -qam doc;                   expect "committed *.md" same same
echo "id = 2" > cases/study.toml;      expect "uncommitted *.toml" same same
echo "1,2" >> cases/data.csv;          git commit -qam data; expect "committed *.toml, *.csv" same same
echo "int cmp2;" >> compare/other.cpp; expect "uncommitted comparator source" differs same
git commit -qam cmp;                   expect "committed comparator source" same same
echo "int st2;" >> app/study.cpp;     expect "uncommitted application source" differs same
git commit -qam app;                   expect "committed application source" same same
echo "int gen2;" >> app/generate.cpp; expect "uncommitted case writer (app/generate.cpp)" differs differs
git commit -qam gen;                   expect "committed case writer" same same
echo "int u2;" >> util/u.cpp;          expect "uncommitted utility source" differs differs
git commit -qam util;                  expect "committed utility source" same same
echo "int s2;" >> sph/a.cpp;           expect "uncommitted solver source" differs differs
git commit -qam sph;                   expect "committed solver source" same same
echo "int n;" > sph/new.cpp;           expect "untracked solver source" differs differs
git add sph/new.cpp; git commit -qm new; expect "the same file committed" same same
rm reference/w.cpp;                    expect "a deleted solver source" differs differs
if [ "$failures" -ne 0 ]; then
  echo "$failures expectation(s) failed"
  exit 1
fi
echo "fingerprints: documentation, specs and data keep both; the comparator only source_fingerprint; solver code both"
