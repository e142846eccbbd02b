#!/bin/bash
# Simulator benchmark (issue 4). Builds sim_bench + rir-simulate in a build directory and prints
# the tables recorded in bench/RESULTS.md, then times rir-simulate end to end (files included).
#   bench/sim/run.sh [build-dir] [--quick]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build-sim-bench}
quick=${2:-}
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DTSRIR_WITH_TORCH=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
ninja -C "$build" sim_bench rir-simulate >/dev/null
echo "machine: $("$root/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%F)"
"$build/bin/sim_bench" $quick

# End to end: 200 reference-room RIRs with random absorption drawn per RIR, written as int16 WAVs.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for i in $(seq -w 1 200); do
  echo "ref$i room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.$(( (10#$i % 9) + 2 ))"
done > "$tmp/rooms.txt"
echo
echo "## rir-simulate end to end: 200 RIRs (T60 0.2-1.0 s, 1.0 s, int16 WAV + lists)"
echo "| threads | wall s | ms per RIR |"
echo "|---|---|---|"
for t in 1 2 4 8 16; do
  [ "$t" -gt "$("$root/utils/cores")" ] && break
  start=$(date +%s.%N)
  "$build/bin/rir-simulate" --num-threads=$t "$tmp/rooms.txt" "$tmp/out$t" 2>/dev/null
  end=$(date +%s.%N)
  awk -v t=$t -v s="$start" -v e="$end" 'BEGIN { printf "| %d | %.3f | %.2f |\n", t, e - s, 1000 * (e - s) / 200 }'
  if [ "$t" -gt 1 ]; then cmp -s "$tmp/out1/ref001.wav" "$tmp/out$t/ref001.wav" || echo "OUTPUT DIFFERS WITH THREADS"; fi
done
