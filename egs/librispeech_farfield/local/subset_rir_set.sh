#!/usr/bin/env bash
# Writes the subset of an RIR set whose ids are listed in <ids>: <out-dir>/rir.scp and
# <out-dir>/rir_list (Kaldi reverberate_data_dir.py format). The audio stays where it is.
# Room ids come from <in-dir>/rir_list when it exists, else from --meta (<rir-id> <room-id> ...).
# Every listed id must be in the set.
set -euo pipefail
meta=""
help_message="Usage: $0 [--meta <rir-table>] <ids> <in-dir-with-rir.scp> <out-dir>"
. ./local/parse_options.sh
[ $# -eq 3 ] || { echo "$help_message" >&2; exit 1; }
ids=$1; in=$2; out=$3
for f in "$ids" "$in/rir.scp"; do [ -s "$f" ] || { echo "$0: missing or empty $f" >&2; exit 1; }; done
mkdir -p "$out"
awk 'NR == FNR {want[$1] = 1; next} ($1 in want) {print; seen[$1] = 1}
     END {for (id in want) if (!(id in seen)) {print "missing " id > "/dev/stderr"; bad = 1}; exit bad}' \
  "$ids" "$in/rir.scp" | sort >"$out/rir.scp.tmp" || { echo "$0: ids of $ids missing in $in/rir.scp" >&2; exit 1; }
if [ -f "$in/rir_list" ]; then
  awk 'NR == FNR {want[$1] = 1; next}
       {for (i = 1; i < NF; i++) if ($i == "--rir-id") {if ($(i + 1) in want) print; next}}' \
    "$ids" "$in/rir_list" | LC_ALL=C sort -k2,2 >"$out/rir_list.tmp"
else
  [ -s "$meta" ] || { echo "$0: $in has no rir_list and no --meta table was given" >&2; exit 1; }
  awk 'NR == FNR {room[$1] = $2; next}
       {if (!($1 in room)) {print "no room for " $1 > "/dev/stderr"; exit 1}
        print "--rir-id " $1 " --room-id " room[$1] " " $2}' "$meta" "$out/rir.scp.tmp" >"$out/rir_list.tmp"
fi
[ "$(wc -l <"$out/rir.scp.tmp")" -eq "$(wc -l <"$out/rir_list.tmp")" ] || {
  echo "$0: $in: rir.scp and rir_list disagree on the ids of $ids" >&2; exit 1; }
mv "$out/rir.scp.tmp" "$out/rir.scp"
mv "$out/rir_list.tmp" "$out/rir_list"
