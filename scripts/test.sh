#!/usr/bin/env bash
# Installs what is missing, builds, and runs the test suite (everything not tagged [slow]); then, unless
# --unit-only, the CI's reliability steps: the short set of unit tests under AddressSanitizer and
# UndefinedBehaviorSanitizer (scripts/sanitize.sh --short, its own build in ./build-sanitize: about
# 15 min on 2 cores) and every fuzz target for FUZZ_SECONDS (default 60) each (scripts/fuzz.sh, Clang,
# ./build-fuzz: about 10 min).
# The long validation runs have their own command: scripts/validate.sh
# Usage: scripts/test.sh [--unit-only]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
unit_only=0
if (($# > 1)); then echo "usage: scripts/test.sh [--unit-only]" >&2; exit 2; fi
case "${1:-}" in
  "") ;;
  --unit-only) unit_only=1 ;;
  *) echo "usage: scripts/test.sh [--unit-only]" >&2; exit 2 ;;
esac

stage() { echo; echo "=== test.sh: $* ($(date -u +%T))"; }
stage "build and unit tests"
"$here/scripts/setup.sh" "$build_dir"
(cd "$build_dir" && ctest -LE slow --output-on-failure --timeout 900 -j 1)
((unit_only)) && exit 0

stage "sanitizers (AddressSanitizer, UndefinedBehaviorSanitizer) on the short set"
"$here/scripts/sanitize.sh" --short
stage "fuzzing the readers, ${FUZZ_SECONDS:-60} s a target"
"$here/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"
stage "done"
