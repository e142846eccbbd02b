#!/usr/bin/env bash
# A Kaldi data directory from unsorted tables: <src>/{wav.scp,utt2spk[,text,spk2gender,utt2uniq,
# segments,reco2dur]} are copied sorted (LC_ALL=C) into <dst>, spk2utt is made from utt2spk
# (Kaldi's utils/utt2spk_to_spk2utt.pl). Duplicate ids are errors. The result replaces <dst>
# only when complete.
set -euo pipefail
help_message="Usage: $0 <src-dir> <dst-dir>"
. ./local/parse_options.sh
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
src=$1; dst=$2
for f in wav.scp utt2spk; do [ -s "$src/$f" ] || { echo "$0: missing or empty $src/$f" >&2; exit 1; }; done
tmp=$dst.tmp.$$
rm -rf "$tmp"; mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT
for f in wav.scp utt2spk text spk2gender utt2uniq segments reco2dur; do
  [ -f "$src/$f" ] || continue
  dup=$(awk '{print $1}' "$src/$f" | LC_ALL=C sort | uniq -d | head -n 3)
  [ -z "$dup" ] || { echo "$0: $src/$f: duplicate ids: $dup" >&2; exit 1; }
  LC_ALL=C sort "$src/$f" >"$tmp/$f"
done
awk '{if (!($2 in seen)) {order[++n] = $2; seen[$2] = 1}; utts[$2] = utts[$2] " " $1}
     END {for (i = 1; i <= n; i++) print order[i] utts[order[i]]}' "$tmp/utt2spk" | LC_ALL=C sort >"$tmp/spk2utt"
rm -rf "$dst"
mv "$tmp" "$dst"
trap - EXIT
