#!/usr/bin/env bash
# rir-metrics speed and memory: 1,000 generated 1 s / 16 kHz RIRs through the program with 1 and
# 2 threads (table and both definitions), peak RSS for 1,000 vs 4,000 RIRs (streamed: it should
# not grow), and the in-process cost per RIR without file I/O.
# Usage: bench/metrics/run_bench.sh [build-dir]   (default: build-metrics next to this repo's src)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build-metrics}
bin=$build/bin
for t in rir-metrics metrics_bench; do
  [[ -x $bin/$t ]] || { echo "missing $bin/$t (ninja -C $build rir-metrics metrics_bench)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $("$here/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$bin/metrics_bench" generate "$work" 1000
# 4,000 entries: the 1,000 files listed four times under distinct ids (memory does not depend on
# the content, only on how the program holds what it has read).
for r in 0 1 2 3; do sed "s/^/r$r-/" "$work/rir.scp"; done > "$work/rir4000.scp"

# Runs the program, prints wall time, user+sys CPU and peak RSS of that one child (os.wait4).
measure() {
  python3 - "$@" <<'PY'
import os, sys, time, subprocess
label, args = sys.argv[1], sys.argv[2:]
t = time.monotonic()
p = subprocess.Popen(args, stdout=subprocess.DEVNULL)
_, status, ru = os.wait4(p.pid, 0)
wall = time.monotonic() - t
if status != 0:
    sys.exit(f"{label}: exit status {status}")
n = int(label.split()[1])
print(f"{label:<32} {wall:8.3f} {1e3 * wall / n:10.3f} {ru.ru_utime + ru.ru_stime:8.3f} {ru.ru_maxrss / 1024:9.1f}")
PY
}
echo
printf "%-32s %8s %10s %8s %9s\n" "# run (definition rirs threads)" "wall_s" "ms/rir" "cpu_s" "rss_MB"
for def in iso irstats; do
  for th in 1 2; do
    measure "$def 1000 $th" "$bin/rir-metrics" --definition=$def --bands --num-threads=$th "$work/rir.scp"
  done
done
measure "iso 4000 2" "$bin/rir-metrics" --num-threads=2 "$work/rir4000.scp"
measure "iso 4000 2 json" "$bin/rir-metrics" --num-threads=2 --format=json "$work/rir4000.scp"
echo
echo "# in-process, no file I/O, one thread"
"$bin/metrics_bench" 1000 16000 1.0
"$bin/metrics_bench" 200 48000 1.0
