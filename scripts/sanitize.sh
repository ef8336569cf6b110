#!/usr/bin/env bash
# Builds the unit tests with AddressSanitizer and UndefinedBehaviorSanitizer (CMake option
# HYDROJUMP_SANITIZE) into ./build-sanitize and runs them; the first error a sanitizer finds stops its
# test with a stack trace, and the script exits non-zero.
#
# Which tests: the unit tests of util/, cases/, sph/ and compare/ and the study runner's (test_util, test_cases, sph_tests,
# compare_tests, test_study), without the [slow] ones. The tests that run the whole program or OpenFOAM
# (compare_integration_tests, reference_*) run in the plain build only: under the sanitizers their
# solver runs take several times longer, and OpenFOAM's own processes are not instrumented.
# --short leaves out the cases labelled "long" as well (tagged [long]: over ~20 s each under the
# sanitizers: the longer verification runs, e.g. still water, the lifted dam-break gate, the piston and
# held-toe basins, the whole-directory comparisons): what the CI runs, the tests ~5 minutes on two
# cores after a build of ~10. The short set still runs every reader, the checkpoint write/resume, the
# Poiseuille and dam-break runs at dx 0.04 m, every combination of the SPH options, and the study
# runner with its kills. --short must come first.
# Needs the Debian packages of scripts/setup.sh (scripts/test.sh installs them first).
# Usage: scripts/sanitize.sh [--short] [extra ctest arguments, e.g. -R "kernels"]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${SANITIZE_BUILD_DIR:-$here/build-sanitize}"
targets=(test_util test_cases sph_tests compare_tests test_study)
exclude="slow"
if [ "${1:-}" = "--short" ]; then
  exclude="slow|long"
  shift
fi

cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHYDROJUMP_SANITIZE=address,undefined
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]}"

# halt_on_error: the first report fails the test. Leak checking stays on.
export ASAN_OPTIONS="halt_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
regex="^($(IFS='|'; echo "${targets[*]}")):"
cd "$build_dir"
ctest -LE "$exclude" -R "$regex" --output-on-failure --timeout 900 -j 1 "$@"
