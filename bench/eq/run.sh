#!/usr/bin/env bash
# rir-eq speed benchmark: 1,000 one-second 16 kHz RIRs (see bench/eq/eq_bench.cc); prints a table.
# Usage: bench/eq/run.sh [build-dir (default: build)] [num-rirs (1000)] [threads (2)]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
ninja -C "$build" eq_bench >/dev/null
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $("$root/utils/cores") cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')), load average $(cut -d' ' -f1 /proc/loadavg)"
"$build/bin/eq_bench" "${2:-1000}" "${3:-2}"
