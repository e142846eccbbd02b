#!/bin/bash
# rir-diagnose benchmark (issue 8): the full diagnosis (2 simulations per RIR, features, detection,
# fitting, held-out evaluation, report) of the 170 one-second R3VIVAL RIRs (48 kHz, analysed at
# 16 kHz) with 1 and 2 threads. Target: < 60 s on 2 cores.
#   bench/diagnose/run.sh [build-dir]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build-diagnose-bench}
data=$root/../shared/data/rirs/r3vival
[ -d "$data" ] || { echo "$0: $data not found (the R3VIVAL data of the workplace)" >&2; exit 1; }
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DTSRIR_WITH_TORCH=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
ninja -C "$build" rir-diagnose >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$root/docs/results/make_r3vival_inputs.sh" "$data" "$tmp/in" 2>/dev/null
echo "machine: $("$root/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u '+%F %H:%M') UTC"
echo "| RIRs | threads | wall s | CPU s (user+sys) | peak RSS MB |"
echo "|---|---|---|---|---|"
for t in 1 2; do
  /usr/bin/time -f "%e %U %S %M" -o "$tmp/time$t" \
    "$build/bin/rir-diagnose" --num-threads=$t "$tmp/in/rooms.txt" "$tmp/in/rir.scp" "$tmp/out$t" >/dev/null 2>&1
  read -r wall user sys rss < "$tmp/time$t"
  echo "| $(wc -l < "$tmp/in/rir.scp") | $t | $wall | $(echo "$user + $sys" | bc) | $((rss / 1024)) |"
done
