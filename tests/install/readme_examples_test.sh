#!/usr/bin/env bash
# `cmake --install` and README.md's examples (issue 32): installs this build tree into a prefix,
# moves the prefix elsewhere, checks that nothing installed refers to the build tree, then runs every
# example of README.md as printed (readme_examples.py) against the moved prefix, with the build and
# source trees hidden (an empty tmpfs mounted over each in a private mount namespace, `unshare -m`:
# the installed programs and module must run on their own). Where unshare is not permitted the
# examples still run against the prefix, with a message that the trees were not hidden.
# Env (set by CTest): TSRIR_BUILD_DIR, TSRIR_PYTHON (the python3 the module is built for).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
: "${TSRIR_BUILD_DIR:?TSRIR_BUILD_DIR must name the CMake build tree}"
build=$(cd "$TSRIR_BUILD_DIR" && pwd)
py=${TSRIR_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset PYTHONPATH
export LC_ALL=C

cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" ||
  { cat "$tmp/install.log" >&2; echo "FAIL: cmake --install" >&2; exit 1; }
mv "$tmp/prefix" "$tmp/moved"
prefix=$tmp/moved
echo "ok: cmake --install into a prefix, then moved to $prefix"
shopt -s nullglob
sitedirs=("$prefix"/lib/python3*/site-packages)
installed=("$prefix"/bin/*)
[ ${#installed[@]} -ge 13 ] || { echo "FAIL: only ${#installed[@]} programs installed in $prefix/bin" >&2; exit 1; }
if [ -f "$build/CMakeCache.txt" ] && grep -q '^TSRIR_PYTHON_MODULE:INTERNAL=ON' "$build/CMakeCache.txt"; then
  [ ${#sitedirs[@]} -eq 1 ] && [ -f "${sitedirs[0]}/tsrir/__init__.py" ] ||
    { echo "FAIL: the Python package is not installed under $prefix/lib/python3*/site-packages" >&2; exit 1; }
  installed+=("${sitedirs[0]}"/tsrir/_tsrir*.so)
fi
for f in "${installed[@]}"; do
  if readelf -d "$f" | grep -E 'RPATH|RUNPATH' | grep -qF "$build"; then
    echo "FAIL: $f has an RPATH into the build tree" >&2; exit 1
  fi
  if grep -qaF "$build" "$f"; then
    echo "FAIL: $f holds the build tree's path $build" >&2; exit 1
  fi
done
echo "ok: no installed program or module refers to the build tree (${#installed[@]} files)"

work=$tmp/work
mkdir -p "$work/ex" "$tmp/pybin"
ln -s "$py" "$tmp/pybin/python3"
have_shared=0
if [ -d "$src/../shared/data" ]; then ln -s "$(cd "$src/../shared" && pwd)" "$work/shared"; have_shared=1; fi
have_torch=0
[ -x "$prefix/bin/ts-rirgan-train" ] && have_torch=1
export PATH="$prefix/bin:$tmp/pybin:$PATH"
bash "$here/prepare_readme_inputs.sh" "$src" "$work/ex" "$work/shared/data" ||
  { echo "FAIL: preparing the README's inputs" >&2; exit 1; }
cp -r "$prefix/share/tsrir/conf" "$work/ex/conf"
cp -r "$prefix/share/tsrir/examples/python" "$work/ex/examples/python"
cp "$src/README.md" "$here/readme_examples.py" "$tmp/"

run=(env PATH="$PATH" PYTHONPATH="${sitedirs[0]:-}" TSRIR_HAVE_SHARED=$have_shared TSRIR_HAVE_TORCH_PROGRAMS=$have_torch
     OMP_NUM_THREADS=1 "$py" "$tmp/readme_examples.py" "$tmp/README.md" "$work/ex" "$@")
# The build tree first: it may lie inside the source tree.
if unshare -m true 2>/dev/null; then
  echo "ok: running the README's examples with $build and $src hidden"
  unshare -m bash -c 'mount -t tmpfs tsrir-hidden "$1" && mount -t tmpfs tsrir-hidden "$2" && shift 2 && exec "$@"' \
    _ "$build" "$src" "${run[@]}"
else
  echo "NOTE: unshare -m is not permitted here: the examples run against $prefix with the build tree still in place"
  "${run[@]}"
fi
