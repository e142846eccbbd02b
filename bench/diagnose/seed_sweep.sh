#!/bin/bash
# Robustness of the hidden-effect suite over draws: re-runs every case of tests/diagnose
# (Catalog, Confounds and OutOfCatalog: positions and hidden parameters redrawn by
# TSRIR_DIAGNOSE_SEED_OFFSET=k) for k = 0 .. N-1 and prints the table docs and bench/RESULTS.md
# quote: per case, how many draws passed every assertion (detection, gain, recovery).
#   bench/diagnose/seed_sweep.sh [build-dir] [N (10)]
# JOBS=N runs N draws at a time (default 1).
# FILTER=<gtest filter> restricts it to some cases (default 'Catalog/*:Confounds/*:OutOfCatalog/*', all of them).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
n=${2:-10}
# A build tree is brought up to date; a bare copy of the binary (another machine) is used as is.
[ ! -f "$build/build.ninja" ] || ninja -C "$build" diagnose_test >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $("$root/utils/cores") cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u '+%F %H:%M') UTC; draws k = 0..$((n - 1)); cases ${FILTER:-Catalog/*:Confounds/*:OutOfCatalog/*}"
# One gtest process per draw, JOBS at a time (default 1: each case already uses 2 threads); each
# draw writes its own file, concatenated in draw order, so the table does not depend on JOBS.
draw() {
  TSRIR_DIAGNOSE_SEED_OFFSET=$1 "$build/bin/diagnose_test" --gtest_filter="${FILTER:-Catalog/*:Confounds/*:OutOfCatalog/*}" 2>/dev/null |
    grep -E '^\[ +(OK|FAILED) +\] (Catalog|Confounds|OutOfCatalog)/.* ms\)$' | sed -E 's/^\[ +(OK|FAILED) +\] ([A-Za-z]+)\/[^/]*\/([a-z0-9_]+).*/\2 \3 \1/' > "$tmp/draw.$(printf %04d "$1")" || true
}
export -f draw
export build tmp FILTER
seq 0 $((n - 1)) | xargs -P "${JOBS:-1}" -I{} bash -c 'draw {}'
cat "$tmp"/draw.* > "$tmp/all"
echo
echo "| suite | case | draws passed |"
echo "|---|---|---|"
awk '{ key = $1 " | " $2; n[key]++; if ($3 == "OK") ok[key]++; if (!(key in seen)) { seen[key] = 1; order[++m] = key } }
     END { for (i = 1; i <= m; ++i) { k = order[i]; printf "| %s | %d/%d |\n", k, ok[k] + 0, n[k]; t += n[k]; to += ok[k] } printf "| all | all cases | %d/%d |\n", to, t }' "$tmp/all"
