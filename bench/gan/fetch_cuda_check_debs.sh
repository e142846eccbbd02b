#!/usr/bin/env bash
# Downloads (here, on a Debian 12 machine with the package registry) the Debian packages that
# bench/gan/cuda_check.sh unpacks on a GPU machine that lacks them and has no network: the
# toolkit's build dependencies other than LibTorch (headers, static/shared libraries and CMake
# configs) and the run-time libraries that io/ loads with dlopen (libsndfile, libsox) with theirs.
# Into exp/cuda_check_debs/ (ignored by git; ~17 MB), which the GPU run carries along.
# Usage: bench/gan/fetch_cuda_check_debs.sh [dir]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
dir=${1:-$here/exp/cuda_check_debs}
packages=(
  libfftw3-dev libfftw3-single3                                  # fftw3.h, libfftw3f.a (linked statically)
  libeigen3-dev                                                  # headers (src/eq)
  libboost1.74-dev libboost-program-options1.74-dev libboost-program-options1.74.0  # src/util
  libgtest-dev                                                   # the tests' static libgtest
  libsndfile1-dev libsndfile1 libflac12 libogg0 libvorbis0a libvorbisenc2 libopus0 libmpg123-0 libmp3lame0
  libsox-dev libsox3 libgsm1 libltdl7 libmagic1 libmagic-mgc libpng16-16
)
mkdir -p "$dir"
cd "$dir"
rm -f ./*.deb
apt-get download "${packages[@]}" >&2
echo "fetch_cuda_check_debs: $(ls ./*.deb | wc -l) packages, $(du -sh . | cut -f1) in $dir" >&2
