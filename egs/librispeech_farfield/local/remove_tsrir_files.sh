#!/usr/bin/env bash
# Removes the files tsrir wrote into a directory (those its .tsrir-owned marker lists), the marker,
# and the directory if nothing else is left: never a file of the user's (docs/robustness.md).
# Usage: remove_tsrir_files.sh <dir>...   (a directory without a marker is left alone)
set -euo pipefail
for dir in "$@"; do
  [ -f "$dir/.tsrir-owned" ] || continue
  while IFS=$'\t' read -r f _; do
    case $f in '#'*|''|*/*) ;; *) rm -f -- "$dir/$f" ;; esac
  done <"$dir/.tsrir-owned"
  rm -f -- "$dir/.tsrir-owned"
  rmdir -- "$dir" 2>/dev/null || echo "remove_tsrir_files.sh: kept $dir: it holds files tsrir did not write" >&2
done
