#!/usr/bin/env bash
# The main job as a fresh clone outside this workplace sees it (issue 14): the repository's tracked
# files copied to a temporary directory whose ../shared does not exist, then
# `run.sh --demo --demo-size tiny` (what utils/run_demo.sh runs after building) with the built
# programs. It must finish, report every stage, say which stand-ins it used, and print Table 1.
# Before the fix it exited 1 with no message right after "stage 0" (a signature loop under
# `set -e`). Exit 77 (skipped) when the GAN programs were not built (the demo needs them).
# Env: TSRIR_BIN = the directory of the built programs (set by CTest).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
for p in ts-rirgan-train gas-to-real; do
  [ -x "$TSRIR_BIN/$p" ] || { echo "SKIP: $p not built (TSRIR_WITH_TORCH=OFF); the demo needs it"; exit 77; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
clone=$tmp/clone/tsrir   # ../shared = $tmp/clone/shared: absent
mkdir -p "$clone"
if git -C "$repo" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  # Tracked files only (as a clone has them; their working-tree state, so uncommitted edits count).
  (cd "$repo" && git ls-files -z | while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
    xargs -0 cp --parents -t "$clone")
else
  (cd "$repo" && tar --exclude=./build --exclude='./build-*' -cf - .) | (cd "$clone" && tar -xf -)
fi
[ ! -e "$clone/../shared" ] || { echo "FAIL: $clone/../shared exists; the test cannot hide it" >&2; exit 1; }
[ -x "$clone/egs/librispeech_farfield/run.sh" ] || { echo "FAIL: the copy has no run.sh" >&2; exit 1; }

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else fail "$what"; fi; }

start=$SECONDS
(cd "$clone/egs/librispeech_farfield" && TSRIR_BIN=$TSRIR_BIN ./run.sh --demo --demo-size tiny) >"$tmp/out" 2>"$tmp/err"
rc=$?
echo "the tiny demo in a bare clone: exit $rc after $((SECONDS - start)) s"
if [ $rc -ne 0 ]; then
  tail -n 30 "$tmp/err" >&2
  fail "run.sh --demo --demo-size tiny exited with $rc in a bare clone"
  # Silence is the defect this test exists for: a failing run must say why.
  check "the failing run printed an ERROR line" grep -q 'ERROR' "$tmp/err"
  exit 1
fi
for s in 0 1 2 3 4 5 6 7; do
  check "stage $s finished" grep -q "^run.sh: stage $s done" "$tmp/err"
done
check "stage 0 says the audio is stand-ins (no ../shared)" grep -qi 'stand-in' "$tmp/err"
for set in real 'GAS' 'GAS+EQ' 'G(GAS)' 'G(GAS+EQ)' 'G(GAS)+EQ'; do
  check "Table 1 printed with the row $set" awk -v s="$set" '$1 == s && NF >= 6 {f = 1} END {exit !f}' "$tmp/out"
done
check "RESULTS.md holds Table 1" grep -q 'Table 1' "$clone/egs/librispeech_farfield/demo/RESULTS.md"
if [ "$failures" -gt 0 ]; then echo "$failures check(s) failed" >&2; exit 1; fi
echo "the bare-clone demo passed"
