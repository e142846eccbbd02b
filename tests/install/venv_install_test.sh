#!/usr/bin/env bash
# `pip install .` into a fresh virtual environment and a wheel, as README's "Installing" section
# prints them: python3 -m venv --system-site-packages (numpy from Debian's python3-numpy), then
# pip install --no-build-isolation . from the source root; python3 -m build --no-isolation --wheel
# and that wheel installed into a second venv. Each venv's tsrir is then imported and used from a
# directory outside the source and build trees (check_installed_module.py), with no PYTHONPATH.
# The extension comes from this build tree (TSRIR_BUILD_DIR, setup.py checks that it is this
# source's and built for this interpreter's ABI) so that the test costs seconds, not a rebuild;
# the fresh-tree path of setup.py is the same code with a configure step before it.
# The source distribution (`python3 -m build --no-isolation` without --wheel makes it first and
# builds the wheel from it): it must hold every file git tracks that the module's CMake build reads
# (MANIFEST.in), and a CMake tree configures from it unpacked as setup.py configures one; building
# that tree is the fresh-tree path (minutes), not run here. (Checked: without MANIFEST.in the sdist
# lacks 281 of those files and this fails.)
# Env (set by CTest): TSRIR_BUILD_DIR, TSRIR_PYTHON (the python3 the module is built for).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
: "${TSRIR_BUILD_DIR:?TSRIR_BUILD_DIR must name the CMake build tree}"
py=${TSRIR_PYTHON:-python3}
for m in venv ensurepip setuptools wheel build; do
  if ! "$py" -c "import $m" 2>/dev/null; then
    echo "FAIL: $py has no '$m' module: apt-get install python3-venv python3-pip python3-setuptools python3-wheel python3-build" >&2
    exit 1
  fi
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset PYTHONPATH PYTHONHOME
# Offline, and nothing outside $tmp: pip's cache, ~.
export HOME=$tmp/home PIP_CACHE_DIR=$tmp/pip-cache PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1
mkdir -p "$HOME" "$tmp/outside"
cp "$here/check_installed_module.py" "$tmp/outside/"   # run from outside: sys.path[0] is the script's dir

# The lines README prints must be the lines run here.
for line in 'python3 -m venv --system-site-packages ~/venvs/tsrir' \
            '~/venvs/tsrir/bin/pip install --no-build-isolation .' \
            'python3 -m build --no-isolation --wheel'; do
  grep -qF -- "$line" "$src/README.md" || { echo "FAIL: README.md no longer prints '$line'" >&2; exit 1; }
done

check_venv() {  # <venv> <what>
  local rp
  for so in "$1"/lib/python3*/site-packages/tsrir/_tsrir*.so; do
    rp=$(readelf -d "$so" | grep -E 'RPATH|RUNPATH' || true)
    case $rp in *"$TSRIR_BUILD_DIR"*|*"$src"*) echo "FAIL: $so keeps a path into the build tree: $rp" >&2; exit 1 ;; esac
  done
  (cd "$tmp/outside" && "$1/bin/python" check_installed_module.py "$1" "$src" "$TSRIR_BUILD_DIR") ||
    { echo "FAIL: $2: the installed module does not work outside the source tree" >&2; exit 1; }
  echo "ok: $2"
}

start=$SECONDS
cd "$src"
"$py" -m venv --system-site-packages "$HOME/venvs/tsrir"
"$HOME/venvs/tsrir/bin/pip" install --no-build-isolation . >"$tmp/pip.log" 2>&1 ||
  { tail -n 30 "$tmp/pip.log" >&2; echo "FAIL: pip install --no-build-isolation . in a fresh venv" >&2; exit 1; }
check_venv "$HOME/venvs/tsrir" "pip install --no-build-isolation . into a fresh venv ($((SECONDS - start)) s)"

start=$SECONDS
"$py" -m build --no-isolation --wheel --outdir "$tmp/dist" . >"$tmp/build.log" 2>&1 ||
  { tail -n 30 "$tmp/build.log" >&2; echo "FAIL: python3 -m build --no-isolation --wheel" >&2; exit 1; }
wheels=("$tmp"/dist/tsrir-*.whl)
[ ${#wheels[@]} -eq 1 ] && [ -f "${wheels[0]}" ] || { echo "FAIL: no wheel in $tmp/dist" >&2; exit 1; }
"$py" -m venv --system-site-packages "$tmp/wheel-venv"
(cd "$tmp/outside" && "$tmp/wheel-venv/bin/pip" install "${wheels[0]}") >"$tmp/pip2.log" 2>&1 ||
  { tail -n 30 "$tmp/pip2.log" >&2; echo "FAIL: pip install ${wheels[0]##*/}" >&2; exit 1; }
check_venv "$tmp/wheel-venv" "wheel ${wheels[0]##*/} built and installed into another venv ($((SECONDS - start)) s)"

start=$SECONDS
# From a copy of the files git knows (tracked and untracked-not-ignored): an old
# src/python/tsrir.egg-info/SOURCES.txt in the tree would otherwise add what MANIFEST.in no longer does.
sdist_src=$src
if command -v git >/dev/null && git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  sdist_src=$tmp/source-copy
  mkdir "$sdist_src"
  (cd "$src" && git ls-files -z --cached --others --exclude-standard | xargs -0 tar --ignore-failed-read -cf - 2>/dev/null) | tar -xf - -C "$sdist_src"
fi
(cd "$sdist_src" && "$py" -m build --no-isolation --sdist --outdir "$tmp/dist" .) >"$tmp/sdist.log" 2>&1 ||
  { tail -n 30 "$tmp/sdist.log" >&2; echo "FAIL: python3 -m build --no-isolation --sdist" >&2; exit 1; }
sdists=("$tmp"/dist/tsrir-*.tar.gz)
[ ${#sdists[@]} -eq 1 ] && [ -f "${sdists[0]}" ] || { echo "FAIL: no sdist in $tmp/dist" >&2; exit 1; }
mkdir "$tmp/sdist"
tar -xzf "${sdists[0]}" -C "$tmp/sdist" --strip-components=1
if command -v git >/dev/null && git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  missing=$(cd "$src" && git ls-files CMakeLists.txt setup.py pyproject.toml src bin conf examples |
            while read -r f; do [ -e "$tmp/sdist/$f" ] || echo "$f"; done)
  [ -z "$missing" ] || { echo "FAIL: the sdist lacks files git tracks: $(echo $missing | head -c 400)" >&2; exit 1; }
fi
cmake -S "$tmp/sdist" -B "$tmp/sdist-build" -DTSRIR_WITH_TORCH=OFF -DTSRIR_BUILD_TESTS=OFF \
      -DPython3_EXECUTABLE="$py" >"$tmp/sdist-cmake.log" 2>&1 ||
  { tail -n 30 "$tmp/sdist-cmake.log" >&2; echo "FAIL: CMake cannot configure the sdist ${sdists[0]##*/}" >&2; exit 1; }
grep -q '^TSRIR_PYTHON_MODULE:INTERNAL=ON' "$tmp/sdist-build/CMakeCache.txt" ||
  { echo "FAIL: the sdist's CMake tree does not build the Python module" >&2; exit 1; }
echo "ok: sdist ${sdists[0]##*/} holds the tracked sources and configures the module ($((SECONDS - start)) s)"
