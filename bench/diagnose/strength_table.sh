#!/bin/bash
# The strength table of one effect for diagnose_probe's --strength (bench/diagnose/diagnose_probe.cc):
# the detector's statistic against the hidden parameter, the mean over seeds 1-4 (48 RIRs each) of
# the tests' independent generator, one line per level.
#   bench/diagnose/strength_table.sh <build-dir> <effect> "<probe arguments, %G = the level>" "<levels>"
# e.g. the dense modal field (room_modes decided on it):
#   bench/diagnose/strength_table.sh build room_modes \
#     "--effects=room_modes --dense-modes --fix=modal_gain_db=%G,modal_decay_factor=1" "-24 -18 -12 -6 0"
# SEEDS="1 2 3 4" by default; JOBS=N probes at a time (default 2).
set -euo pipefail
build=${1:?usage: $0 <build-dir> <effect> "<probe args with %G>" "<levels>"}
effect=${2:?effect}
args=${3:?probe arguments}
levels=${4:?levels}
seeds=${SEEDS:-1 2 3 4}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u '+%F %H:%M') UTC; $effect; seeds $seeds"
for g in $levels; do
  for s in $seeds; do echo "$g $s"; done
done > "$tmp/jobs"
run_one() {  # <level> <seed>
  local a=${args//%G/$1}
  # shellcheck disable=SC2086
  "$build/bin/diagnose_probe" --count=48 --seed="$2" $a 2>/dev/null |
    awk -v e="$effect" -v g="$1" -v s="$2" '$1 == "stat" && $2 == e { print g, s, $4, $3 }' > "$tmp/res.$1.$2"
}
export -f run_one
export build effect args tmp
xargs -P "${JOBS:-2}" -L 1 bash -c 'run_one "$@"' _ < "$tmp/jobs"
echo "| level | mean statistic | detected |"
echo "|---|---|---|"
for g in $levels; do
  cat "$tmp"/res."$g".* | awk -v g="$g" '{ s += $3; d += $4; n++ } END { printf "| %s | %.4f | %d/%d |\n", g, s / n, d, n }'
done
