#!/usr/bin/env bash
# TS-RIRGAN translation-fidelity suite over several seeds (issue 17): for each seed, new data
# (tests/gan/fidelity_domains.cc), a model trained with the given ts-rirgan-train options, held-out
# synthetic RIRs translated, and every measure printed (tests/gan/fidelity_measures.h), then the
# pass count. One LibTorch thread per run; JOBS runs in parallel (default 2).
# Usage: bench/gan/fidelity_seeds.sh [build-dir] [seeds, e.g. "1 2 3 4 5"] ["ts-rirgan-train options"]
# Default options: the program's defaults at the width, batch and steps issue 17 names.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build}
seeds=${2:-1 2 3 4 5}
args=${3:---width=16 --batch-size=4 --steps=1000}
suite=$build/bin/gan-fidelity-suite
[[ -x $suite ]] || { echo "missing $suite (ninja -C $build gan-fidelity-suite)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg); options: $args"
run_seed() {
  "$suite" "$build/bin" "$work/seed$1" "$1" "$args" 1 > "$work/seed$1.out" 2>&1 || true
}
export -f run_seed
export args suite build work
printf '%s\n' $seeds | xargs -P "${JOBS:-2}" -I{} bash -c 'run_seed {}'
passed=0
for s in $seeds; do
  cat "$work/seed$s.out"
  grep -q '; PASS$' "$work/seed$s.out" && passed=$((passed + 1))
done
echo "passed $passed of $(echo $seeds | wc -w) seeds"
