#!/usr/bin/env bash
# One translation-fidelity run (tests/gan/fidelity_suite.h) measured along its training, not only at
# its end (issue 34: is a kept parameter's drift there from the start, does it grow, does it recede?).
# Trains with gan-fidelity-suite as fidelity_seeds.sh does, with --checkpoint-every=EVERY; keeps a
# copy of each checkpoint as it is written (ts-rirgan-train overwrites checkpoint.pt); then for each
# copy translates the run's held-out synthetic RIRs with gas-to-real and prints the suite's measures
# (gan-fidelity-suite --remeasure), one line per step (two for a model that keeps a weight average:
# with it and with the last weights), and the end-of-run line; a failed translation is reported
# and the next checkpoint measured.
# Usage: bench/gan/fidelity_trajectory.sh <build-dir> <kind> <seed> <steps> <every> "<ts-rirgan-train options>" <new-out-dir>
# The out dir keeps the run's work dir (work/), the copies (ckpt.STEP.pt) and a translation per copy
# (at.STEP/); `bench/gan/translation_level_change.py --bands OUT/at.STEP` reads one.
set -euo pipefail
[[ $# == 7 ]] || { sed -n '2,12p' "$0" >&2; exit 1; }
build=$1 kind=$2 seed=$3 steps=$4 every=$5 args=$6 out=$7
bin=$build/bin
[[ -x $bin/gan-fidelity-suite ]] || { echo "missing $bin/gan-fidelity-suite" >&2; exit 1; }
[[ ! -e $out ]] || { echo "$out exists; give a new directory" >&2; exit 1; }
mkdir -p "$out"
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $(getconf _NPROCESSORS_ONLN) cores, load: $(cut -d' ' -f1-3 /proc/loadavg); kind $kind seed $seed; options: $args --steps=$steps --checkpoint-every=$every"
OMP_NUM_THREADS=1 "$bin/gan-fidelity-suite" --effect="$kind" "$bin" "$out/work" "$seed" \
  "$args --steps=$steps --checkpoint-every=$every" 1 keep > "$out/run.out" 2>&1 &
run=$!
checkpoint=$out/work/model/checkpoint.pt last=""
copy_new_checkpoint() {  # checkpoint.pt is written to a temporary name and renamed: a copy is whole
  [[ -f $checkpoint ]] || return 0
  local stamp
  stamp=$(stat -c %Y.%s "$checkpoint" 2>/dev/null) || return 0
  [[ $stamp != "$last" ]] || return 0
  last=$stamp
  # Written at multiples of EVERY (and at the end): the loss log's last step, rounded down.
  local step
  step=$(tail -n 1 "$out/work/model/loss_log.csv" | cut -d, -f1)
  ((step >= steps)) || step=$((step / every * every))
  cp "$checkpoint" "$out/ckpt.$step.pt"
}
while kill -0 "$run" 2>/dev/null; do copy_new_checkpoint; sleep 5; done
wait "$run" || true
copy_new_checkpoint
# A model that keeps a weight average (--generator-average-decay) is measured twice per checkpoint:
# translated with the average (gas-to-real's default; at.STEP/) and with the last step's weights
# (at.STEP.last/); the same training run, so the two lines differ by the averaging alone.
averaged=$(grep -c '^generator_average_decay' "$out/work/model/settings.txt" || true)
measure() {  # step dir label [gas-to-real options]
  local c=$1 at=$2 label=$3
  shift 3
  mkdir -p "$at/model"
  cp "$out/work/model/settings.txt" "$at/model/"
  ln "$out/ckpt.$c.pt" "$at/model/checkpoint.pt"
  ln -s "$out/work/test_syn" "$at/test_syn"
  if ! OMP_NUM_THREADS=1 "$bin/gas-to-real" --model="$at/model" --keep-length=input --num-threads=1 "$@" \
    "$at/test_syn/rir.scp" "$at/sr" 2> "$at/translate.log"; then
    echo "step $c$label: translation failed ($(tail -n 1 "$at/translate.log"))"
    return 0
  fi
  echo "step $c$label: $("$bin/gan-fidelity-suite" --effect="$kind" --remeasure "$at" "$seed" | tail -n 1)"
}
for c in $(ls "$out"/ckpt.*.pt | sed -E 's/.*ckpt\.([0-9]+)\.pt/\1/' | sort -n); do
  if ((averaged)); then
    measure "$c" "$out/at.$c" " (averaged weights)"
    measure "$c" "$out/at.$c.last" " (last weights)" --use-last-weights
  else
    measure "$c" "$out/at.$c" ""
  fi
done
echo "end of run: $(grep '^seed' "$out/run.out" | tail -n 1)"
echo "# done $(date -u +%Y-%m-%dT%H:%MZ), load: $(cut -d' ' -f1-3 /proc/loadavg)"
