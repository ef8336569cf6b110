#!/usr/bin/env bash
# Fuzzes the readers of untrusted files with libFuzzer (Debian's clang; tests/fuzz/): the study spec,
# CSV tables, SPH checkpoints, ParaView collections and validation records. Builds into ./build-fuzz with
# -fsanitize=fuzzer-no-link,address and runs each target for SECONDS (default 60) on a working copy of
# its seed corpus (tests/fuzz/corpus/<target>/). A crash, an uncaught exception, an input that takes
# over 10 s or an allocation over 2 GB stops that target and writes the input to
# build-fuzz/artifacts/<target>/; the script exits 1 once every target has run. Make each such input a
# regression test. A longer run: scripts/fuzz.sh 3600.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET ...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
((${#targets[@]})) || targets=(fuzz_spec fuzz_tables fuzz_checkpoint fuzz_pvd fuzz_record)
build_dir="${FUZZ_BUILD_DIR:-$here/build-fuzz}"

# shellcheck source=scripts/packages.sh
source "$here/scripts/packages.sh"
install_missing_packages clang libclang-rt-14-dev

cmake -S "$here" -B "$build_dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHYDROJUMP_SANITIZE=fuzzer-no-link,address -DHYDROJUMP_FUZZ=ON -DHYDROJUMP_BUILD_TESTS=OFF
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]}"

failed=()
for t in "${targets[@]}"; do
  work="$build_dir/corpus/$t"
  artifacts="$build_dir/artifacts/$t/"
  mkdir -p "$work" "$artifacts"
  echo "fuzz: $t for $seconds s (seed corpus tests/fuzz/corpus/$t)"
  if ! ASAN_OPTIONS="detect_leaks=0" "$build_dir/tests/fuzz/$t" -max_total_time="$seconds" -timeout=10 \
       -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$artifacts" \
       "$work" "$here/tests/fuzz/corpus/$t" > "$build_dir/$t.log" 2>&1; then
    failed+=("$t")
    tail -40 "$build_dir/$t.log"
  fi
  grep -E "stat::number_of_executed_units|stat::new_units_added" "$build_dir/$t.log" | tr '\n' ' ' || true
  echo
done
if ((${#failed[@]})); then
  echo "fuzz: FAILED: ${failed[*]} (inputs in $build_dir/artifacts/)"
  exit 1
fi
echo "fuzz: every target ran $seconds s without a finding"
