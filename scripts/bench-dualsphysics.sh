#!/usr/bin/env bash
# hydrojump's dam-break benchmark beside DualSPHysics 5.4 CPU on the same case, alternating, so that
# the machine's drift hits both alike (README, Performance).
#
# Usage: scripts/bench-dualsphysics.sh DSPH_DIR [ROUNDS] [THREADS ...]
#   DSPH_DIR  a DualSPHysics checkout (github.com/DualSPHysics/DualSPHysics) with its CPU solver built,
#             without Chrono, wave generation or MoorDynPlus:
#               cd src/source && make -f Makefile_cpu COMPILE_CHRONO=NO COMPILE_WAVEGEN=NO COMPILE_MOORDYNPLUS=NO
#             and GenCase in bin/linux/GenCase_linux64 (or GENCASE=path). GenCase ships as a prebuilt
#             binary only; where the current one is missing from a checkout, v5.0's from the history
#             (commit 1dfd0cd) writes cases that 5.4 reads.
#   ROUNDS    rounds of each pair (default 3); THREADS: thread counts (default 1 2).
# Environment: HYDROJUMP (default build/hydrojump), END_TIME (default 0.3 s).
#
# The case is DualSPHysics' examples/main/01_DamBreak/CaseDambreakVal2D_Def.xml (a 1 m x 2 m column in
# a 4 m tank, dp = 0.01 m, Wendland, artificial viscosity 0.02, Fourtakas diffusion, DBC, Verlet,
# CFL 0.2, coefsound 20) with three wall layers, no gauges and no output but the last, run with
# -sv:none: 23,015 particles, as `hydrojump bench`'s (23,032). Both count only the time steps:
# DualSPHysics' "Steps per second" x particles, hydrojump's particle-steps per second.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dsph="${1:?usage: scripts/bench-dualsphysics.sh DSPH_DIR [ROUNDS] [THREADS ...]}"
rounds="${2:-3}"
shift $(( $# >= 2 ? 2 : 1 ))
threads=("$@")
[ ${#threads[@]} -gt 0 ] || threads=(1 2)
hydrojump="${HYDROJUMP:-$here/build/hydrojump}"
gencase="${GENCASE:-$dsph/bin/linux/GenCase_linux64}"
solver="$dsph/bin/linux/DualSPHysics5.4CPU_linux64"
example="$dsph/examples/main/01_DamBreak/CaseDambreakVal2D_Def.xml"
end_time="${END_TIME:-0.3}"
for f in "$hydrojump" "$gencase" "$solver"; do
  [ -x "$f" ] || { echo "bench-dualsphysics: $f is missing or not executable" >&2; exit 2; }
done
[ -f "$example" ] || { echo "bench-dualsphysics: $example is missing" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$example" "$work/Dam_Def.xml" "$end_time" <<'EOF'
import re, sys
source, target, end_time = sys.argv[1:]
xml = open(source).read()
xml = re.sub(r"<special>.*?</special>", "", xml, flags=re.S)  # no gauges
box = '<size x="4" y="2" z="3" />'
if box not in xml:
    sys.exit("bench-dualsphysics: the example's tank box has changed; update this script")
xml = xml.replace(box, box + '\n                        <layers vdp="0,1,2" />')  # three wall layers
xml = re.sub(r'(key="TimeMax" value=")[^"]*', r"\g<1>" + end_time, xml)
xml = re.sub(r'(key="TimeOut" value=")[^"]*', r"\g<1>" + end_time, xml)
open(target, "w").write(xml)
EOF
cp "$dsph/bin/linux/DsphConfig.xml" "$work/" 2>/dev/null || true
(cd "$work" && "$gencase" Dam_Def out/Dam -save:all > gencase.log 2>&1) ||
  { echo "bench-dualsphysics: GenCase failed (log: $work/gencase.log)" >&2; cat "$work/gencase.log" >&2; exit 1; }
particles="$(grep -o 'Total particles: [0-9]*' "$work/gencase.log" | grep -o '[0-9]*$')"
echo "case: $particles particles, 0-$end_time s; hydrojump: $("$hydrojump" --version)"

dualsphysics() {  # threads -> M particle-steps/s
  rm -rf "$work/run"
  "$solver" "$work/out/Dam" "$work/run" -sv:none "-ompthreads:$1" > "$work/run.log" 2>&1 ||
    { echo "bench-dualsphysics: DualSPHysics failed:" >&2; tail -20 "$work/run.log" >&2; exit 1; }
  local sps
  sps="$(grep 'Steps per second' "$work/run.log" | grep -o '[0-9.]*$')"
  /usr/bin/python3 -c "print(round($sps * $particles / 1e6, 3))"
}
hydrojump_bench() {  # threads -> M particle-steps/s
  "$hydrojump" bench --threads "$1" --end-time "$end_time" | grep -o '[0-9.]* M particle-steps/s' | head -1 | grep -o '^[0-9.]*'
}

printf '%-8s %-6s %12s %12s %8s\n' threads round DualSPHysics hydrojump ratio
for t in "${threads[@]}"; do
  ratios=()
  for ((r = 1; r <= rounds; ++r)); do
    d="$(dualsphysics "$t")"
    h="$(hydrojump_bench "$t")"
    ratio="$(/usr/bin/python3 -c "print(round($h / $d, 2))")"
    ratios+=("$ratio")
    printf '%-8s %-6s %12s %12s %8s\n' "$t" "$r" "$d M" "$h M" "${ratio}x"
  done
  echo "threads $t: median ratio $(printf '%s\n' "${ratios[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')x"
done
