#!/usr/bin/env bash
# A Kaldi data directory for one LibriSpeech part (<LibriSpeech>/<part>/<reader>/<chapter>/
# <reader>-<chapter>-<n>.flac and <reader>-<chapter>.trans.txt), as Kaldi's
# egs/librispeech/s5/local/data_prep.sh makes it: utterance ids <reader>-<chapter>-<n>, speaker
# <reader>-<chapter>, wav.scp entries "flac -c -d -s <file> |", text, utt2spk, spk2utt, and
# spk2gender from SPEAKERS.TXT when present.
set -euo pipefail
help_message="Usage: $0 <LibriSpeech/part-dir> <data-dir>   e.g.: $0 corpora/LibriSpeech/dev-clean data/dev_clean"
. ./local/parse_options.sh
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
[ -d "$1" ] || { echo "$0: no such directory $1" >&2; exit 1; }
src=$(readlink -f "$1"); dst=$2
command -v flac >/dev/null || { echo "$0: flac is not installed (utils/bootstrap.sh installs it)" >&2; exit 1; }
tmp=$dst.tmp.$$
rm -rf "$tmp"; mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT
find "$src" -mindepth 3 -maxdepth 3 -name '*.trans.txt' | LC_ALL=C sort >"$tmp/trans_files"
[ -s "$tmp/trans_files" ] || { echo "$0: no */*/*.trans.txt under $src" >&2; exit 1; }
while read -r t; do
  d=$(dirname "$t")
  awk -v d="$d" -v f="$t" 'NF < 1 {next}
    { if ($1 !~ /^[0-9]+-[0-9]+-[0-9]+$/) {print f ":" NR ": bad utterance id " $1 > "/dev/stderr"; exit 1}
      print $1 " flac -c -d -s " d "/" $1 ".flac |" >> "'"$tmp"'/wav.scp.u"
      spk = $1; sub(/-[0-9]+$/, "", spk); print $1 " " spk >> "'"$tmp"'/utt2spk.u"
      print >> "'"$tmp"'/text.u" }' "$t"
done <"$tmp/trans_files"
# Every transcribed utterance must have its audio (Kaldi's data_prep.sh checks the counts).
awk '{print $6}' "$tmp/wav.scp.u" | while read -r f; do [ -f "$f" ] || { echo "$0: missing $f" >&2; exit 1; }; done
for f in wav.scp utt2spk text; do LC_ALL=C sort -u "$tmp/$f.u" >"$tmp/$f"; rm "$tmp/$f.u"; done
awk '{spk[$2] = spk[$2] " " $1} END {for (s in spk) print s spk[s]}' "$tmp/utt2spk" | LC_ALL=C sort >"$tmp/spk2utt"
spk_file=$(dirname "$src")/SPEAKERS.TXT
if [ -f "$spk_file" ]; then
  awk -F'|' 'NR == FNR {gsub(/ /, "", $1); gsub(/ /, "", $2); g[$1] = tolower($2); next}
             {split($0, f, " "); r = f[1]; sub(/-.*/, "", r); if (r in g) print f[1], g[r]}' "$spk_file" "$tmp/spk2utt" >"$tmp/spk2gender"
fi
rm "$tmp/trans_files"
rm -rf "$dst"
mv "$tmp" "$dst"
trap - EXIT
echo "$0: $(wc -l <"$dst/wav.scp") utterances, $(wc -l <"$dst/spk2utt") speakers in $dst" >&2
