#!/usr/bin/env bash
# TS-RIRGAN speed and memory: training step time and peak RSS at width 16 and 64 (batch 4), and
# gas-to-real throughput at width 64 (batched and unbatched). Inputs: the 170 measured R3VIVAL RIRs
# (48 kHz, resampled to 16 kHz by the programs) as both domains; the content does not change the
# cost. Step times are the median of the logged per-step wall times after the first (warm-up) step.
# The width-16 step is measured at 1 and at [threads] threads; OPENBLAS_NUM_THREADS=1 (the program
# also sets it). PROFILE=1 adds a perf profile (top shared objects and symbols) of the width-16 run.
# Usage: bench/gan/run_bench.sh [build-dir] [threads] [width-64 steps]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build-gan}
threads=${2:-2}
steps64=${3:-3}
bin=$build/bin
for t in ts-rirgan-train gas-to-real; do
  [[ -x $bin/$t ]] || { echo "missing $bin/$t (ninja -C $build $t)" >&2; exit 1; }
done
data=$here/../shared/data/rirs/r3vival
[[ -d $data ]] || { echo "needs ../shared/data/rirs/r3vival (real RIRs)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for f in "$data"/*.wav; do b=$(basename "$f" .wav); echo "$b $f"; done > "$work/rir.scp"
n=$(wc -l < "$work/rir.scp")
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), --num-threads=$threads"
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

# median of step_s over steps >= 2 of a loss log
median_step() { awk -F, 'NR>2{print $NF}' "$1" | sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'; }

echo "| run | median wall s/step | CPU s/step (process) | peak RSS MB |"
echo "|---|---|---|---|"
export OPENBLAS_NUM_THREADS=1
for spec in "16 12 1" "16 12 $threads" "64 $steps64 $threads"; do
  set -- $spec
  w=$1; s=$2; t=$3
  m=$work/m${w}_t$t
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$bin/ts-rirgan-train" --real="$work/rir.scp" \
    --synthetic="$work/rir.scp" --width=$w --batch-size=4 --steps=$s --num-threads=$t \
    --checkpoint-every=100000 --progress-interval=60 "$m" 2> "$work/log"
  read -r wall user sys rss < "$work/time"
  cpu=$(awk -v u="$user" -v s="$sys" -v n="$s" 'BEGIN{printf "%.3f", (u+s)/n}')
  echo "| train width $w, batch 4, $t thread(s), $s steps (CPU/step includes loading $n RIRs) | $(median_step "$m/loss_log.csv") | $cpu | $((rss / 1024)) |"
done
if [[ ${PROFILE:-0} == 1 ]]; then
  perf record -q -o "$work/perf.data" "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" \
    --width=16 --batch-size=4 --steps=12 --num-threads=1 --progress-interval=60 "$work/mprof" 2> /dev/null
  echo; echo "perf, width 16, 1 thread (whole run incl. loading): top shared objects / symbols"
  perf report -q -i "$work/perf.data" --sort dso 2> /dev/null | head -8 || true
  perf report -q -i "$work/perf.data" --sort sym 2> /dev/null | head -15 || true
fi

echo
echo "| translation (width 64, $n RIRs) | RIRs/s (wall, excl. model load) | CPU s total | peak RSS MB |"
echo "|---|---|---|---|"
for b in 16 1; do
  /usr/bin/time -f "%e %U %S %M" -o "$work/time_t$b" "$bin/gas-to-real" --model="$work/m64_t$threads" \
    --batch-size=$b --num-threads=$threads "$work/rir.scp" "$work/out$b" 2> "$work/log_t$b"
  read -r wall user sys rss < "$work/time_t$b"
  rate=$(grep -o '[0-9.e+]* RIRs/s' "$work/log_t$b" | cut -d' ' -f1)
  echo "| gas-to-real --batch-size=$b | $rate | $(awk -v u="$user" -v s="$sys" 'BEGIN{printf "%.1f", u+s}') | $((rss / 1024)) |"
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
