#!/bin/bash
# Microphone arrays (issue 33): CPU time of rir-simulate per source position for one microphone
# and for an 8-microphone circular array (radius 4.25 cm) at the same positions, 1.0 s RIRs at
# 16 kHz, float WAVs written; the issue's target is <= 2x one microphone.
#   bench/sim/array_speed.sh [bin-dir] [positions] [repeats]
set -euo pipefail
bin=$(cd "${1:-build/bin}" && pwd)
n=${2:-100}
reps=${3:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck source=bench/sim/array_lists.sh
source "$(dirname "$0")/array_lists.sh"
write_array_lists "$tmp" "$n"
# The smallest CPU time (user + sys) of `reps` runs, per source position, in ms.
cpu_ms() {
  local best=""
  for r in $(seq 1 "$reps"); do
    local t
    t=$( { /usr/bin/time -f '%U %S' "$bin/rir-simulate" --model="$1" --format=float --length=1.0 --overwrite=true \
           "$tmp/$2.txt" "$tmp/out_$2" 2>&1 >/dev/null; } | tail -1 | awk '{ print $1 + $2 }')
    best=$(awk -v a="$best" -v b="$t" 'BEGIN { print (a == "" || b < a) ? b : a }')
  done
  awk -v t="$best" -v n="$n" 'BEGIN { printf "%.3f", 1000 * t / n }'
}
cd "$tmp"
echo "| model | 1 mic, CPU ms per source position | 8 mics | 8 mics / 1 mic |"
echo "|---|---|---|---|"
for model in gas ism; do
  one=$(cpu_ms "$model" one)
  eight=$(cpu_ms "$model" eight)
  awk -v m="$model" -v a="$one" -v b="$eight" 'BEGIN { printf "| %s | %.3f | %.3f | %.1fx |\n", m, a, b, b / a }'
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
