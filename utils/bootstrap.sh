#!/usr/bin/env bash
# Installs the Debian packages the toolkit needs (when missing), then configures and builds it out of
# tree in build/ (override with BUILD_DIR). Used by run_demo.sh and run_tests.sh.
# Not root and packages missing: prints the exact apt-get line and exits 1.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}

packages=(build-essential cmake ninja-build pkg-config
          libtorch-dev libopenblas0-pthread libsndfile1-dev libsox-dev libsox-fmt-all sox
          libfftw3-dev libeigen3-dev libboost-program-options-dev libgtest-dev
          espeak-ng flac bible-kjv   # bible-kjv: the TTS corpus's sentences (stage 8 --asr proxy)
          python3-dev pybind11-dev python3-numpy python3-torch
          # pip install . / python3 -m build (tests/install/venv_install_test.sh, README "Installing")
          python3-venv python3-pip python3-setuptools python3-wheel python3-build)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "bootstrap: missing Debian packages. Run as root:" >&2
    echo "  $cmd" >&2
    exit 1
  fi
  echo "bootstrap: installing ${missing[*]}" >&2
  bash -c "$cmd" >&2
fi

cmake_args=(-S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release)
[ -n "${TSRIR_CMAKE_ARGS:-}" ] && read -r -a extra <<<"$TSRIR_CMAKE_ARGS" && cmake_args+=("${extra[@]}")
echo "bootstrap: configuring and building in $build_dir" >&2
cmake "${cmake_args[@]}" >&2
# Each LibTorch translation unit needs ~1.4 GB of RAM to compile; 2 jobs fit the smallest machines.
ninja -C "$build_dir" -j "${TSRIR_BUILD_JOBS:-$("$root/utils/cores")}" >&2
