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
data=$here/../shared/data/rirs/r3vival
[[ -d $data ]] || { echo "needs ../shared/data/rirs/r3vival (real RIRs)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for f in "$data"/*.wav; do echo "$(basename "$f" .wav) $f"; done > "$work/rir.scp"
n=$(wc -l < "$work/rir.scp")
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "# previous: $prev; new: $new; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
median_step() { awk -F, 'NR>3{print $NF}' "$1" | sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'; }
"$new/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=64 --batch-size=4 --steps=3 \
  --num-threads=2 --checkpoint-every=100000 --progress-interval=60 "$work/m64" 2> /dev/null
translate() {  # build-name bin batch: one measured gas-to-real run
  rm -rf "$work/out"
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$2/gas-to-real" --model="$work/m64" --batch-size=$3 \
    --num-threads=2 "$work/rir.scp" "$work/out" 2> "$work/log"
  read -r wall user sys rss < "$work/time"
  echo "round $r $1: gas-to-real width 64, batch $3: whole process $wall s ($(awk -v w="$wall" -v n="$n" \
    'BEGIN{printf "%.1f", n / w}') RIRs/s), user $user s, sys $sys s, peak RSS $((rss / 1024)) MB;" \
    "$(grep -o 'model load [0-9.e-]* s, [0-9.]* RIRs/s' "$work/log")"
}
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
  translate "new, first process after the trainings" "$new" 16
  for build in previous new; do
    bin=$prev; [[ $build == new ]] && bin=$new
    for b in 16 32; do translate "$build" "$bin" $b; done
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
