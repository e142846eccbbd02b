#!/usr/bin/env bash
# The main job on embedded data: installs what is missing, builds, then runs the recipe
# egs/librispeech_farfield/run.sh --demo (see README: which parts are stand-ins), and checks that
# its Table 1 holds finite numbers (the GAN's collapse guard is ts-rirgan-train's own).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/utils/bootstrap.sh"
cd "$root/egs/librispeech_farfield"
./run.sh --demo "$@"
results=demo/RESULTS.md
if [ -f "$results" ] && grep -q '^## Table 1' "$results"; then
  # Table 1's rows: every number must be finite (a nan/inf means a set's RIRs are unmeasurable).
  if sed -n '/^## Table 1/,/^## /p' "$results" | grep -v '^#' | grep -qiE '(^|[^a-z])(-?nan|-?inf)([^a-z]|$)'; then
    echo "run_demo.sh: ERROR: Table 1 in $PWD/$results has non-finite numbers:" >&2
    sed -n '/^## Table 1/,/^## /p' "$results" | grep -iE 'nan|inf' >&2
    exit 1
  fi
  echo "run_demo.sh: Table 1 in $PWD/$results: all numbers finite"
fi
