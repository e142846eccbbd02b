#!/usr/bin/env bash
# Combines Kaldi data directories (as Kaldi's utils/combine_data.sh): the union of wav.scp,
# utt2spk, text (and spk2gender, utt2uniq, segments, reco2dur when every source has them), sorted,
# with spk2utt regenerated. Ids must be unique across the sources.
set -euo pipefail
help_message="Usage: $0 <dst-dir> <src-dir1> <src-dir2> ..."
. ./local/parse_options.sh
[ $# -ge 3 ] || { echo "$help_message" >&2; exit 1; }
dst=$1; shift
tmp=$dst.tmp.$$
rm -rf "$tmp"; mkdir -p "$tmp/in"
trap 'rm -rf "$tmp"' EXIT
for f in wav.scp utt2spk text spk2gender utt2uniq segments reco2dur; do
  all=true
  for d in "$@"; do [ -f "$d/$f" ] || all=false; done
  if [ "$f" = wav.scp ] || [ "$f" = utt2spk ]; then
    [ "$all" = true ] || { echo "$0: every source needs $f" >&2; exit 1; }
  fi
  [ "$all" = true ] || continue
  for d in "$@"; do cat "$d/$f"; done >"$tmp/in/$f"
done
"$(dirname "$0")/make_data_dir.sh" "$tmp/in" "$tmp/out"
rm -rf "$dst"
mv "$tmp/out" "$dst"
rm -rf "$tmp"
trap - EXIT
echo "$0: $(wc -l <"$dst/utt2spk") utterances from $# dirs in $dst" >&2
