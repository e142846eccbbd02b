#!/usr/bin/env bash
# All tests: installs what is missing, builds from scratch (out of tree), runs every ctest test.
# Tests that need ../shared/data skip with a message when it is absent.
#
# Then the sanitizer stage: the library unit tests again, built with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DTSRIR_SANITIZE=ON, no LibTorch) in $ASAN_BUILD_DIR (default
# build-asan). Only fast tests of library code run there (sanitized code is 2-5x slower and each
# extra area costs build time): the gtest binaries in sanitize_tests below plus the ctest label
# "sanitize" (the fuzz-corpus replays of tests/robustness). The stage takes ~5-10 min on a
# 2-core machine. TSRIR_SANITIZER_STAGE=0 skips it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/utils/bootstrap.sh"
# The machine's cores, whatever OMP_NUM_THREADS says (utils/cores says why).
cores=$("$root/utils/cores")
# Torch and OpenBLAS would each start one thread per core inside every test process.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
status=0
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$cores" "$@" || status=$?

if [ "${TSRIR_SANITIZER_STAGE:-1}" != 0 ]; then
  asan_dir=${ASAN_BUILD_DIR:-$root/build-asan}
  # Library unit tests (no program runs, no LibTorch), each well under a minute sanitized.
  sanitize_tests=(util_test io_test dsp_test robustness_input_test metrics_tests sim_tests eq_unit_test)
  echo "run_tests: sanitizer stage (ASan + UBSan) in $asan_dir" >&2
  start=$(date +%s)
  cmake -S "$root" -B "$asan_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTSRIR_SANITIZE=ON \
    -DTSRIR_WITH_TORCH=OFF >&2
  known=$(ninja -C "$asan_dir" -t targets all | cut -d: -f1)
  targets=()
  for t in "${sanitize_tests[@]}"; do
    grep -qx "$t" <<<"$known" && targets+=("$t")
  done
  replays=$(grep -x 'fuzz_replay_[a-z_]*' <<<"$known" || true)
  ninja -C "$asan_dir" -j "${TSRIR_BUILD_JOBS:-$cores}" "${targets[@]}" $replays >&2
  # Leaks inside system libraries on malformed input (listed there, with why) are not ours.
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export LSAN_OPTIONS=suppressions=$root/tests/robustness/lsan.supp
  for t in "${targets[@]}"; do
    echo "run_tests: [sanitized] $t" >&2
    "$asan_dir/bin/$t" --gtest_brief=1 || { echo "run_tests: [sanitized] $t FAILED" >&2; status=1; }
  done
  ctest --test-dir "$asan_dir" --output-on-failure -j "$cores" -L sanitize -R '^robustness\.fuzz_replay\.' || status=1
  echo "run_tests: sanitizer stage took $(( $(date +%s) - start )) s" >&2
fi
exit $status
