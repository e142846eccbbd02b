#!/usr/bin/env bash
# Runs every libFuzzer harness for a bounded time and prints a table of executions and findings.
#
#   tests/robustness/run_fuzzers.sh [SECONDS_PER_HARNESS [HARNESS...]]     (default 60 s, all)
#
# Builds the harnesses first, with clang, in $FUZZ_BUILD_DIR (default build-fuzz; configured with
# -DTSRIR_FUZZ=ON -DTSRIR_WITH_TORCH=OFF). Needs Debian's clang and libclang-rt-14-dev. Each
# harness starts from its checked-in seeds (tests/robustness/corpus/<name>/) plus the corpus it
# grew on earlier runs ($FUZZ_BUILD_DIR/fuzz-corpus/<name>/). A crash, leak, timeout or
# out-of-memory input is saved under $FUZZ_BUILD_DIR/fuzz-artifacts/<name>/ and the harness stops;
# once fixed, copy the input into tests/robustness/corpus/<name>/ so the replay test keeps it.
# Exit status: 0 when no harness found anything.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
seconds=${1:-60}
shift || true
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
jobs=${FUZZ_BUILD_JOBS:-2}

if ! command -v clang++ >/dev/null; then
  echo "run_fuzzers: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2
  exit 1
fi
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DTSRIR_WITH_TORCH=OFF -DTSRIR_FUZZ=ON >&2
else
  cmake "$build" >/dev/null || echo "run_fuzzers: re-configuring $build failed; using the harnesses built before" >&2
fi
ninja -C "$build" -j "$jobs" fuzzers >&2

if [ $# -gt 0 ]; then harnesses=("$@"); else mapfile -t harnesses < "$build/fuzz_harnesses.txt"; fi

printf '%-16s %8s %12s %10s %8s  %s\n' harness seconds executions exec/s corpus findings
status=0
for h in "${harnesses[@]}"; do
  [ -n "$h" ] || continue
  bin="$build/bin/fuzz_$h"
  seeds="$root/tests/robustness/corpus/$h"
  work="$build/fuzz-corpus/$h"
  artifacts="$build/fuzz-artifacts/$h"
  log="$build/fuzz-logs/$h.log"
  mkdir -p "$work" "$artifacts" "$(dirname "$log")" "$seeds"
  before=$(find "$artifacts" -type f | wc -l)
  start=$(date +%s)
  # 2 GB RSS and 10 s per input: an input that needs more is itself a finding (oom-/timeout-).
  set +e
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
    LSAN_OPTIONS=suppressions="$root/tests/robustness/lsan.supp" \
    "$bin" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" "$work" "$seeds" >"$log" 2>&1
  rc=$?
  set -e
  elapsed=$(( $(date +%s) - start ))
  execs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$' | tail -1)
  rate=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$log" | grep -oE '[0-9]+$' | tail -1)
  corpus=$(find "$work" -type f | wc -l)
  after=$(find "$artifacts" -type f | wc -l)
  found="none"
  if [ "$rc" -ne 0 ] || [ "$after" -gt "$before" ]; then
    found="rc=$rc, $((after - before)) new in $artifacts (log: $log)"
    status=1
  fi
  printf '%-16s %8s %12s %10s %8s  %s\n' "$h" "$elapsed" "${execs:-?}" "${rate:-?}" "$corpus" "$found"
done
exit $status
