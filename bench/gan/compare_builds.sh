#!/usr/bin/env bash
# Two builds side by side, in turn in every round: the width-16 training step of the defaults
# (batch 4, median step_s of steps 3-12, 1 and 2 threads) and gas-to-real's whole process (the
# command's wall clock, program start and model load included) on a width-64 defaults model trained
# 3 steps by the second build (so that it has the generator files; a build before them reads the
# checkpoint), --batch-size 16 and 32, 2 threads. Inputs: the 170 measured R3VIVAL
# RIRs (48 kHz, resampled by the programs) as both domains.
# Usage: bench/gan/compare_builds.sh PREVIOUS_BIN_DIR NEW_BIN_DIR [rounds]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
prev=$1; new=$2; rounds=${3:-3}
source "$here/bench/gan/speed_lib.sh"
bench_setup
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $("$here/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "# previous: $prev; new: $new; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$new/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=64 --batch-size=4 --steps=3 \
  --num-threads=2 --checkpoint-every=100000 --progress-interval=60 "$work/m64" 2> /dev/null
for r in $(seq "$rounds"); do
  for build in previous new; do
    bin=$prev; [[ $build == new ]] && bin=$new
    for t in 1 2; do
      rm -rf "$work/m16"
      "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=16 --batch-size=4 --steps=12 \
        --num-threads=$t --progress-interval=60 "$work/m16" 2> /dev/null
      echo "round $r $build: width-16 step, $t thread(s): $(median_step "$work/m16/loss_log.csv") s"
    done
  done
  # On a VM whose host takes back the memory a process frees, the next process's first touches of
  # fresh memory cost more (the first translation after a training run: ~1.6 s more system time
  # on the AMD VM, 2026-12-05): that one is reported as its own row, and the measured runs follow it.
  translate_row "round $r new, first process after the trainings" "$new" 16
  for build in previous new; do
    bin=$prev; [[ $build == new ]] && bin=$new
    for b in 16 32; do translate_row "round $r $build" "$bin" $b; done
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
