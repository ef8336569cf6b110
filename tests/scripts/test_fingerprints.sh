#!/usr/bin/env bash
# The run caches' code fingerprints (cmake/write_version.cmake): documentation (*.md), spec files
# (*.toml) and data (*.csv) never change them; a comparator source changes source_fingerprint only;
# a solver source (committed, uncommitted or untracked) changes source and solver fingerprints and its
# own solver's (sph_fingerprint for sph/, vof_fingerprint for reference/), a shared one (cases/, util/,
# app/generate.*) all four. Runs the script on a small git
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

fingerprints() {  # prints "source solver sph vof"
  "$cmake_exe" -DSRC="$repo" -DVERSION=1.0 -DOUT="$work/version.hpp" -P "$source_dir/cmake/write_version.cmake" >/dev/null
  local name out=""
  for name in source solver sph vof; do
    out+="$(sed -n "s/.* ${name}_fingerprint = \"\(.*\)\";/\1/p" "$work/version.hpp") "
  done
  echo "$out"
}
failures=0
expect() {  # expect WHAT SOURCE SOLVER SPH VOF, each "same" or "differs" against the previous state
  local now
  now="$(fingerprints)"
  local -a a b got
  read -r -a a <<< "$before"
  read -r -a b <<< "$now"
  local i
  for i in 0 1 2 3; do
    if [ -z "${b[$i]:-}" ]; then got[$i]=missing; elif [ "${a[$i]}" = "${b[$i]}" ]; then got[$i]=same; else got[$i]=differs; fi
  done
  if [ "${got[*]}" != "$2 $3 $4 $5" ]; then
    echo "$1: source, solver, sph, vof fingerprints ${got[*]} (expected $2 $3 $4 $5)"
    failures=$((failures + 1))
  fi
  before="$now"
}
before="$(fingerprints)"
case "$before" in *+code.*" "*+code.*" "*+code.*" "*+code.*) ;; *) echo "fingerprints not computed: $before"; exit 1 ;; esac

echo "# more" >> sph/README.md;        expect "uncommitted *.md" same same same same
git commit -qam doc;                   expect "committed *.md" same same same same
echo "id = 2" > cases/study.toml;      expect "uncommitted *.toml" same same same same
echo "1,2" >> cases/data.csv;          git commit -qam data; expect "committed *.toml, *.csv" same same same same
echo "int cmp2;" >> compare/other.cpp; expect "uncommitted comparator source" differs same same same
git commit -qam cmp;                   expect "committed comparator source" same same same same
echo "int st2;" >> app/study.cpp;     expect "uncommitted application source" differs same same same
git commit -qam app;                   expect "committed application source" same same same same
echo "int gen2;" >> app/generate.cpp; expect "uncommitted case writer (app/generate.cpp)" differs differs differs differs
git commit -qam gen;                   expect "committed case writer" same same same same
echo "int u2;" >> util/u.cpp;          expect "uncommitted utility source" differs differs differs differs
git commit -qam util;                  expect "committed utility source" same same same same
echo "int s2;" >> sph/a.cpp;           expect "uncommitted SPH source" differs differs differs same
git commit -qam sph;                   expect "committed SPH source" same same same same
echo "int n;" > sph/new.cpp;           expect "untracked SPH source" differs differs differs same
git add sph/new.cpp; git commit -qm new; expect "the same file committed" same same same same
echo "int c2;" >> cases/spec.cpp;      expect "uncommitted case source" differs differs differs differs
git commit -qam cases;                 expect "committed case source" same same same same
echo "int w2;" >> reference/w.cpp;     expect "uncommitted VOF source" differs differs same differs
git commit -qam ref;                   expect "committed VOF source" same same same same
rm reference/w.cpp;                    expect "a deleted VOF source" differs differs same differs
if [ "$failures" -ne 0 ]; then
  echo "$failures expectation(s) failed"
  exit 1
fi
echo "fingerprints: documentation, specs and data keep all; the comparator only source_fingerprint; a solver's code its own and the shared ones; shared solver code all"
