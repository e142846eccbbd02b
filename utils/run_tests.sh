#!/usr/bin/env bash
# All tests: installs what is missing, builds from scratch (out of tree), runs every ctest test.
# Tests that need ../shared/data skip with a message when it is absent.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/utils/bootstrap.sh"
# Torch and OpenBLAS would each start one thread per core inside every test process.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" "$@"
