#!/usr/bin/env bash
# The proxy experiment's second test set, real read speech (stage 8 --asr proxy): every
# transcribed utterance of <speech-dir> (the workplace's ../shared/data/speech) as one Kaldi data
# dir, read in place (FLAC through Kaldi's usual `flac -c -d -s ... |` pipe):
#   librispeech/*.wav  with librispeech/trans.txt (LibriSpeech test-clean; speaker = reader-chapter)
#   librispeech/*.flac with librispeech/mini_librispeech_text.txt (`lbi-<utt>` lines; dev-clean);
#                      an utterance without a transcript there is left out
#   pocketsphinx/*.wav with pocketsphinx/transcription and cards/*.wav with cards/cards.transcription
#                      (LibriVox read speech, read card names; Debian pocketsphinx-testdata)
# Usage: make_real_speech_dir.sh <speech-dir> <out-data-dir>
# Exit status 2 (and a message) when <speech-dir> lacks these files: the caller skips the test set.
set -euo pipefail
[ $# -eq 2 ] || { sed -n '2,11p' "$0" >&2; exit 1; }
speech=$(readlink -m "$1") out=$2
ls_dir=$speech/librispeech ps_dir=$speech/pocketsphinx
for f in "$ls_dir/trans.txt" "$ps_dir/transcription" "$ps_dir/cards/cards.transcription"; do
  [ -s "$f" ] || { echo "make_real_speech_dir.sh: $f is missing: no real-speech test set" >&2; exit 2; }
done
mkdir -p "$out"
tmp=$out/.tmp.$$
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT
add() {  # <utt> <spk> <rxfilename> <text>
  [ -n "$4" ] || return 0
  printf '%s %s\n' "$1" "$3" >>"$tmp/wav.scp"
  printf '%s %s\n' "$1" "$2" >>"$tmp/utt2spk"
  printf '%s %s\n' "$1" "$4" >>"$tmp/text"
}
: >"$tmp/wav.scp"; : >"$tmp/utt2spk"; : >"$tmp/text"
for w in "$ls_dir"/*.wav; do
  u=$(basename "$w" .wav)
  add "$u" "${u%-*}" "$w" "$(awk -F'\t' -v u="$u" '$1 == u { print $2 }' "$ls_dir/trans.txt")"
done
for f in "$ls_dir"/*.flac; do
  u=$(basename "$f" .flac)
  add "$u" "${u%-*}" "flac -c -d -s $f |" \
    "$(awk -v u="lbi-$u" '$1 == u { $1 = ""; print substr($0, 2) }' "$ls_dir/mini_librispeech_text.txt" 2>/dev/null)"
done
# A pocketsphinx line "<s> words </s> (id)" -> words.
ps_text() { grep "($2)\$" "$1" | sed 's/<s>//; s/<\/s>//; s/([^)]*)$//' | awk '{ $1 = $1; print }'; }
for w in "$ps_dir"/*.wav; do
  id=$(basename "$w" .wav)
  add "ps-austen-${id##*-}" ps-austen "$w" "$(ps_text "$ps_dir/transcription" "$id")"
done
for w in "$ps_dir"/cards/*.wav; do
  id=$(basename "$w" .wav)
  add "ps-cards-$id" ps-cards "$w" "$(ps_text "$ps_dir/cards/cards.transcription" "$id")"
done
[ -s "$tmp/wav.scp" ] || { echo "make_real_speech_dir.sh: no transcribed utterance in $speech" >&2; exit 2; }
for f in wav.scp utt2spk text; do LC_ALL=C sort "$tmp/$f" >"$out/$f"; done
awk '{ a[$2] = a[$2] " " $1 } END { for (s in a) print s a[s] }' "$out/utt2spk" | LC_ALL=C sort >"$out/spk2utt"
echo "make_real_speech_dir.sh: $out: $(wc -l <"$out/wav.scp") utterances, $(wc -l <"$out/spk2utt") speakers" >&2
