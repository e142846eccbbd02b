#!/usr/bin/env bash
# How reliably does the small TS-RIRGAN learn? Runs tests/gan/gan_learning_test (hidden 250 Hz mode
# moved toward the real domain, per-RIR onset kept) once per seed with the test's own options or
# with the options given, and prints one row per seed plus the pass count. One thread per run;
# JOBS runs in parallel (default 2). Each run takes ~75 s of an idle core.
# Usage: bench/gan/learning_seeds.sh [build-dir] [seeds, e.g. "1 2 3 4"] ["ts-rirgan-train options"]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build}
seeds=${2:-1 2 3 4 5 6}
args=${3:-}
test_bin=$build/bin/gan_learning_test
[[ -x $test_bin ]] || { echo "missing $test_bin (ninja -C $build gan_learning_test)" >&2; exit 1; }
if [[ -z $args ]]; then
  # The test's own options (without its --seed).
  args=$(grep -A3 'constexpr const char\* kTrainArgs' "$here/tests/gan/gan_learning_test.cc" | grep -o '"[^"]*"' |
         tr -d '"' | tr '\n' ' ' | sed 's/--seed=[0-9]* //')
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $(nproc) cores; options: $args"
run_seed() {
  TSRIR_GAN_LEARNING_ARGS="$args --seed=$1" "$test_bin" > "$work/seed$1.log" 2>&1 || true
}
export -f run_seed
export args test_bin work
printf '%s\n' $seeds | xargs -P "${JOBS:-2}" -I{} bash -c 'run_seed {}'
echo "| seed | G_SR: 250 Hz moved (of gap; bound > 0.5) | G_RS: moved back (bound > 0.5) | G_SR median onset error ms (bound) | passed |"
echo "|---|---|---|---|---|"
passed=0
for s in $seeds; do
  log=$work/seed$s.log
  moved=$(grep -o 'moved [-0-9.e]* of the gap' "$log" | cut -d' ' -f2)
  back=$(grep -o 'moved [-0-9.e]* back' "$log" | cut -d' ' -f2)
  onset=$(grep -o 'onset error [0-9.]* ms; input-independent baseline [0-9.]*' "$log" | awk '{printf "%s (< %.2f)", $3, 0.5 * $7}')
  ok=no
  grep -q '^\[  PASSED  \] 1 test' "$log" && { ok=yes; passed=$((passed + 1)); }
  echo "| $s | ${moved:-?} | ${back:-?} | ${onset:-?} | $ok |"
done
echo "passed $passed of $(echo $seeds | wc -w)"
