#!/usr/bin/env bash
# The main job on embedded data: installs what is missing, builds, then runs the recipe
# egs/librispeech_farfield/run.sh --demo (see README: which parts are stand-ins).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export BUILD_DIR=${BUILD_DIR:-$root/build}
"$root/utils/bootstrap.sh"
cd "$root/egs/librispeech_farfield"
exec ./run.sh --demo "$@"
