#!/usr/bin/env bash
# The downstream experiment's budget: runs stage 8's proxy path (local/asr/run_proxy.sh) on the
# demo's RIR sets and noise, then prints Table 2 and, per trained model, wall time and peak
# memory (GNU time), with the machine's load. Needs the demo's stages 0-5 first:
#   (cd egs/librispeech_farfield && ./run.sh --demo --stop-stage 6)
# Usage: bench/asr/run_table2.sh [--sets "clean real ..."] [--seeds "0 1 2"] [--out DIR]
#        [--corpus-opts "..."] [--train-opts "..."]
# e.g. the sensitivity check alone: bench/asr/run_table2.sh --sets "clean real" --seeds 0
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
recipe=$root/egs/librispeech_farfield
sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq"
seeds="0 1 2"
out=$recipe/demo/bench_asr
extra=()
while [ $# -gt 0 ]; do
  case $1 in
    --sets) sets=$2 ;; --seeds) seeds=$2 ;; --out) out=$2 ;;
    --corpus-opts) extra+=(--corpus-opts "$2") ;; --train-opts) extra+=(--train-opts "$2") ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
cd "$recipe"
. ./path.sh
rirs=demo/data/rirs
[ -s "$rirs/real_test/rir_list" ] || { echo "$0: run the demo's stages 0-6 first (./run.sh --demo --stop-stage 6)" >&2; exit 1; }
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
start=$SECONDS
local/asr/run_proxy.sh --train-sets "$sets" --seeds "$seeds" ${extra[@]+"${extra[@]}"} \
  "$rirs" demo/data/noise/noise_list "$out/data" "$out/exp"
echo
echo "| model | wall s | peak MB |"
echo "|---|---|---|"
for k in $seeds; do for s in $sets; do
  t=$out/exp/asr/${s}_seed$k/time.txt
  [ -f "$t" ] && awk -v m="${s}_seed$k" '{ printf "| %s | %.0f | %.0f |\n", m, $1, $3 / 1024 }' "$t"
done; done
echo
echo "total $((SECONDS - start)) s (corpus, reverberation, training, decoding; models already trained are skipped); load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
