#!/usr/bin/env bash
# The demo's GAN training (egs/librispeech_farfield/run.sh --demo true: width 8, batch 4) at 1 and
# 2 threads, idle and under a load of two other 1-thread trainings, 20 steps each, alternating
# 1, 2, 1, 2; prints the median step (speed_lib.sh's median_step: steps 3-20) and whether the two
# thread counts wrote the same losses (they should: ts-rirgan-train's two lanes are the 1-thread
# model, GanCli.TwoThreadsTrainAsOne).
# Inputs: the 170 measured R3VIVAL RIRs as both domains, as bench/gan/compare_builds.sh.
# Usage: bench/gan/demo_threads.sh [BIN_DIR (default build/bin)]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=${1:-$here/build/bin}
source "$here/bench/gan/speed_lib.sh"
work=$(mktemp -d)
load_pids=()
trap 'kill "${load_pids[@]}" 2> /dev/null || true; wait 2> /dev/null || true; rm -rf "$work"' EXIT
r3vival_scp "$here/../shared/data/rirs/r3vival"
train() {  # out-dir threads steps
  "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=8 --batch-size=4 \
    --steps="$3" --num-threads="$2" --progress-interval=600 "$1" 2> /dev/null
}
bench_header "$bin"
for condition in idle loaded; do
  if [[ $condition == loaded ]]; then
    # Two 1-thread trainings (the program itself in the background, so that the trap's kill reaches
    # it), long enough to outlast the rounds.
    for l in 1 2; do
      "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=8 --batch-size=4 \
        --steps=100000 --num-threads=1 --seed="$l" --checkpoint-every=100000 "$work/load$l" 2> /dev/null &
      load_pids+=($!)
    done
    sleep 20
  fi
  echo "# $condition: load average before $(cut -d' ' -f1-3 /proc/loadavg)"
  for round in 1 2; do
    for threads in 1 2; do
      rm -rf "$work/t$threads"
      train "$work/t$threads" "$threads" 20
      echo "$condition, round $round: $threads thread(s): median step $(median_step "$work/t$threads/loss_log.csv") s"
    done
    same=$(cmp -s <(cut -d, -f1-12 "$work/t1/loss_log.csv") <(cut -d, -f1-12 "$work/t2/loss_log.csv") && echo yes || echo NO)
    echo "$condition, round $round: losses of 1 and 2 threads identical: $same"
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
