#!/usr/bin/env bash
# One build on the machine at hand: what writing the generator files adds to a checkpoint (the
# times of the checkpoint's and the generator files' writes, from strace's timestamps of each
# temporary file's creation and rename), gas-to-real's whole process at width 64 (3 runs) and the
# width-16 step of the defaults at 2 threads (3 trainings, median step_s of steps 3-12). Inputs:
# the 170 measured R3VIVAL RIRs as both domains, as bench/gan/compare_builds.sh.
# Usage: bench/gan/checkpoint_cost_and_speed.sh [BIN_DIR (default build/bin)]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
bin=${1:-$here/build/bin}
command -v strace > /dev/null || { echo "needs strace" >&2; exit 1; }
source "$here/bench/gan/speed_lib.sh"
bench_setup
bench_header "$bin"
strace -f --seccomp-bpf -tt -e trace=openat,rename,renameat,renameat2 -o "$work/strace.txt" \
  "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=64 --batch-size=4 --steps=3 \
  --num-threads=2 --checkpoint-every=100000 --progress-interval=60 "$work/m64" 2> "$work/train64.log"
# Each .pt file: from its temporary file's creation to its rename.
awk '/\.pt\.tmp\./ && /O_CREAT/ {match($0, /m64\/[^.]*\.pt/); start[substr($0, RSTART + 4, RLENGTH - 4)] = $2}
     /rename[a-z0-9]*\(.*\.pt\.tmp\./ {match($0, /m64\/[^.]*\.pt/); f = substr($0, RSTART + 4, RLENGTH - 4)
       split(start[f], a, ":"); split($2, b, ":")
       printf "write %s: %.2f s\n", f, (b[1] - a[1]) * 3600 + (b[2] - a[2]) * 60 + (b[3] - a[3])}' "$work/strace.txt"
ls -l "$work"/m64/*.pt | awk '{print "size", $NF ":", $5, "bytes"}'
for r in 1 2 3; do translate_row "round $r" "$bin" 16; done
for r in 1 2 3; do
  rm -rf "$work/m16"
  "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" --width=16 --batch-size=4 --steps=12 \
    --num-threads=2 --progress-interval=60 "$work/m16" 2> /dev/null
  echo "round $r: width-16 step, 2 threads: $(median_step "$work/m16/loss_log.csv") s"
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
