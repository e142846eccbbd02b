#!/usr/bin/env bash
# Times the README's main job, egs/librispeech_farfield/run.sh --demo (stages 0-7), from scratch in
# a temporary directory, and prints one row per stage (wall seconds from the recipe's progress
# lines) plus the whole run's wall and CPU time (user+sys of every process it started) and peak
# RSS of the largest process. Target: < 10 minutes on 2 cores.
#   bench/recipe/run_demo_bench.sh [small|tiny] [bin-dir]    (default: small, <repo>/build/bin)
set -euo pipefail
size=${1:-small}
root=$(cd "$(dirname "$0")/../.." && pwd)
export TSRIR_BIN=${2:-${TSRIR_BIN:-$root/build/bin}}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$root/egs/librispeech_farfield/run.sh" --demo --demo-size "$size" \
  --data "$tmp/data" --exp "$tmp/exp" --results "$tmp/RESULTS.md" >"$tmp/out" 2>"$tmp/err" ||
  { tail -n 30 "$tmp/err" >&2; echo "the demo failed" >&2; exit 1; }
read -r wall user sys rss_kb <"$tmp/time"
echo "| stage | wall s | what |"
echo "|---|---|---|"
sed -n 's/^run.sh: stage \([0-9]\) done (\([0-9]*\) s): \(.*\)$/| \1 | \2 | \3 |/p' "$tmp/err" | cut -c1-110
echo
printf 'demo %s: wall %.0f s, CPU %.0f s (user %.0f + sys %.0f), peak RSS %.0f MB, load average %s, %s\n' \
  "$size" "$wall" "$(echo "$user + $sys" | bc)" "$user" "$sys" "$((rss_kb / 1024))" "$(cut -d' ' -f1-3 /proc/loadavg)" "$("$root/utils/cores") cores"
grep -A12 '^# Mean acoustic' "$tmp/out" || true
