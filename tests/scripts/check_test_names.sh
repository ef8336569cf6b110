#!/usr/bin/env bash
# Every Catch2 test case must be runnable by the name CTest registers for it (catch_discover_tests).
# A name that Catch2's test-spec parser reads differently (a ';' splits CMake lists, a leading '~' or
# '*' is a pattern, ...) would make CTest run a spec that matches nothing: Catch2 then exits 0 and
# the test "passes" without running. For each executable given, each listed name, escaped as
# CatchAddTests.cmake does (',', '[', ']'), must select exactly that one test case.
set -uo pipefail
failures=0
checked=0
for exe in "$@"; do
  while IFS= read -r name; do
    [ -n "$name" ] || continue
    checked=$((checked + 1))
    if [[ "$name" == *";"* ]]; then
      echo "$(basename "$exe"): '$name' contains ';' (CTest splits the name there)"
      failures=$((failures + 1))
      continue
    fi
    spec="$name"
    for c in ',' '[' ']'; do spec="${spec//"$c"/\\$c}"; done
    selected="$("$exe" "$spec" --list-test-names-only 2>/dev/null | grep -v '^$')"
    if [ "$selected" != "$name" ]; then
      echo "$(basename "$exe"): '$name' selects: '${selected}'"
      failures=$((failures + 1))
    fi
  done < <("$exe" --list-test-names-only | grep -v '^$')
done
if [ "$failures" -ne 0 ]; then
  echo "$failures of $checked test names cannot be run by CTest as registered"
  exit 1
fi
echo "all $checked test names select exactly their test case"
