#!/usr/bin/env bash
# Lists the functions under a directory (default src/) that are longer than a limit (default 120
# lines, the developers' guide's), longest first, as "<lines> <file>:<first line> <name>", from
# Universal Ctags' definitions (first and end line of each function; lambdas count as part of the
# function they are written in). Exit status 1 when any is listed.
# Usage: utils/long_functions.sh [max_lines] [dir]
set -euo pipefail
max=${1:-120}
dir=${2:-src}
command -v ctags > /dev/null || { echo "long_functions: needs Universal Ctags (apt-get install universal-ctags)" >&2; exit 2; }
ctags -R --languages=C++ --kinds-C++=f --fields=+ne -o - "$dir" 2> /dev/null |
  awk -F'\t' -v max="$max" '
    $1 !~ /^__anon/ {
      line = ""; end = "";
      for (i = 4; i <= NF; ++i) {
        if ($i ~ /^line:/) line = substr($i, 6);
        if ($i ~ /^end:/) end = substr($i, 5);
      }
      if (line != "" && end != "" && end - line + 1 > max) print end - line + 1, $2 ":" line, $1;
    }' |
  sort -rn | { ! grep .; }
