#!/usr/bin/env bash
# The downstream experiment's budget (issue 19: 8 sets x 1 seed within 60 minutes, 3 seeds within
# 3 hours on 2 cores): runs stage 8's proxy path (local/asr/run_proxy.sh, conf/asr-train-proxy.conf)
# on the demo's RIR sets and noise, then prints Table 2 and, per trained model, wall and CPU time
# and peak memory (GNU time), with the machine's load. Needs the demo's stages 0-6 first:
#   (cd egs/librispeech_farfield && ./run.sh --demo --stop-stage 6)
# Usage: bench/asr/run_table2.sh [--sets "clean real ..."] [--seeds "0 1 2"] [--jobs 2] [--out DIR]
#        [--corpus-opts "..."] [--train-opts "..."] [--train-config FILE]
# e.g. the sensitivity check alone: bench/asr/run_table2.sh --sets "clean real" --seeds 0
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
recipe=$root/egs/librispeech_farfield
sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext"
seeds="0 1 2"
jobs=2
out=$recipe/demo/bench_asr
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --sets) sets=$2 ;; --seeds) seeds=$2 ;; --out) out=$2 ;; --jobs) jobs=$2 ;;
    --corpus-opts) extra+=(--corpus-opts "$2") ;; --train-opts) extra+=(--train-opts "$2") ;;
    --train-config) extra+=(--train-config "$(readlink -f "$2")") ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
mkdir -p "$out"; out=$(readlink -f "$out")
cd "$recipe"
. ./path.sh
rirs=demo/data/rirs
for s in $sets; do
  [ "$s" = clean ] || [ -s "$rirs/${s}_train/rir_list" ] ||
    { echo "$0: no $rirs/${s}_train: run the demo's stages 0-6 first (./run.sh --demo --stop-stage 6)" >&2; exit 1; }
done
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# sets: $sets; seeds: $seeds; $jobs model(s) at a time; config: $(grep -v '^#' "$root/conf/asr-train-proxy.conf" | tr '\n' ' ')${extra[*]:+; extra: ${extra[*]}}"
start=$SECONDS
# Load sampled every minute while it runs (the figures below are only comparable at similar load).
( while sleep 60; do cut -d' ' -f1 /proc/loadavg; done ) >"$out/load.txt" &
sampler=$!
trap 'kill $sampler 2>/dev/null || true' EXIT
local/asr/run_proxy.sh --train-sets "$sets" --seeds "$seeds" --jobs "$jobs" --real-speech "$root/../shared/data/speech" \
  ${extra[@]+"${extra[@]}"} "$rirs" demo/data/noise/noise_list "$out/data" "$out/exp"
wall=$((SECONDS - start))
kill $sampler 2>/dev/null || true
echo
echo "| model | wall s | CPU s (user+sys) | peak MB |"
echo "|---|---|---|---|"
for k in $seeds; do for s in $sets; do
  t=$out/exp/asr/log/time_${s}_seed$k.txt
  [ -f "$t" ] && awk -v m="${s}_seed$k" '{ printf "| %s | %.0f | %.0f | %.0f |\n", m, $1, $2 + $3, $4 / 1024 }' "$t"
done; done
echo
cpu=$(awk '{ s += $2 + $3 } END { printf "%.0f", s }' "$out"/exp/asr/log/time_*.txt 2>/dev/null || echo 0)
echo "total: $wall s wall (corpus, reverberation, training, decoding; models already trained are skipped), $cpu s CPU in training;" \
  "load average during the run: $(awk '{ s += $1; n++ } END { if (n) printf "mean %.1f, max %.1f", s / n, m; else print "n/a" } { if ($1 > m) m = $1 }' "$out/load.txt"); at end: $(cut -d' ' -f1-3 /proc/loadavg)"
