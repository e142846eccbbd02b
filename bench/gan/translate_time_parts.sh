#!/usr/bin/env bash
# Where gas-to-real's whole-process time goes at width 64 (issue 34, item 5): the process start
# alone (`gas-to-real --help`: loading LibTorch), perf's split of that start by library where perf
# works, the whole process with a width-2 model (everything but the generator's arithmetic: start,
# reading and resampling the 170 RIRs, writing), and the width-64 generator's forward pass alone
# (gan_forward_bench) at batch 16 (--batch-size=16: 11 groups of 16, the last padded) and 29
# (--batch-size=32: 6 groups of 29). Inputs: the 170 measured R3VIVAL RIRs, as compare_builds.sh.
# Usage: bench/gan/translate_time_parts.sh [BIN_DIR (default build/bin)]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=${1:-$here/build/bin}
source "$here/bench/gan/speed_lib.sh"
bench_setup
bench_header "$bin"
echo "libraries loaded with gas-to-real: $(ldd "$bin/gas-to-real" | wc -l)" \
  "(libtorch_cpu's own DT_NEEDED: $(readelf -d "$(ldd "$bin/gas-to-real" | awk '/libtorch_cpu/ {print $3}')" | grep -c NEEDED))"
for r in 1 2 3; do
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$bin/gas-to-real" --help > /dev/null 2>&1 || true
  read -r wall user sys < "$work/time"
  echo "start alone (gas-to-real --help), run $r: $wall s wall, user $user s, sys $sys s"
done
if perf stat -e task-clock true > /dev/null 2>&1; then
  perf record -q -o "$work/perf.data" "$bin/gas-to-real" --help > /dev/null 2>&1 || true
  echo "start alone, perf's samples by library (top 5):"
  perf report -i "$work/perf.data" --no-children --sort dso -g none 2> /dev/null | grep -v '^#' | grep . | head -5
fi
"$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=2 --batch-size=4 --steps=1 \
  --num-threads=2 --progress-interval=60 "$work/m2" 2> /dev/null
for r in 1 2 3; do translate_row "width-2 model (no arithmetic to speak of), run $r" "$bin" 16 "$work/m2" 2; done
for batch in 16 29; do
  "$bin/gan_forward_bench" --width=64 --decoder=light --generator=band-gain --correction-max-hz=500 \
    --batch="$batch" --threads=2 --reps=5 | awk -v b="$batch" -v n="$n" -F'|' '{
      ms = $9 + 0; groups = int((n + b - 1) / b)
      printf "width-64 forward alone, batch %d: %.1f ms per batch, %.1f RIRs/s; %d groups for %d RIRs: %.2f s\n",
             b, ms, b * 1000 / ms, groups, n, groups * ms / 1000}'
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
