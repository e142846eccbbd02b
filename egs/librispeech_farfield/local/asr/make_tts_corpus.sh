#!/usr/bin/env bash
# A synthetic read-speech corpus for the downstream experiment (stage 8 --asr proxy): public-domain
# English sentences from the King James Bible (Debian package bible-kjv: the `bible` program),
# cut at punctuation into clauses of --min-words..--max-words words whose words are all among the
# --vocab-size most frequent ones, spoken by Debian's text-to-speech engines with a random rate
# and pitch per utterance. Two Kaldi data dirs (speaker = voice): <out>/train (the train voices)
# and <out>/test (the test voices, never heard in training; sentences disjoint from train's).
#
# Usage: make_tts_corpus.sh [options] <out-dir>
#   --train-voices "espeak:en-us+m3 ..."  --test-voices "..."  voices as engine:name, engine one of
#       espeak (espeak-ng voice+variant) or flite (flite -voice name; needs the flite package)
#   --utts-per-train-voice N (50)  --utts-per-test-voice N (40)  --vocab-size N (500)
#   Each utterance is peak-normalised to -3 dBFS at 16 kHz, 16 bit.
#   --min-words N (4)  --max-words N (9)  --books "Gen1:1-50:26 ..."  --seed N (0)  --nj N (2)
# e.g.: local/asr/make_tts_corpus.sh --utts-per-train-voice 50 data/asr/tts
set -euo pipefail
# 24 training voices: every English dialect voice of espeak-ng with two or three of the variants
# m1-m4, m6, f2-f4; the 6 test voices use variants never heard in training (m5, m7, f1, f5).
train_voices="espeak:en-us+m1 espeak:en-us+m3 espeak:en-us+f2 espeak:en-us+f4 espeak:en-gb+m2 espeak:en-gb+m4 espeak:en-gb+f3 espeak:en-gb+m6 espeak:en+m1 espeak:en+f2 espeak:en+m3 espeak:en+f4 espeak:en-gb-scotland+m2 espeak:en-gb-scotland+f3 espeak:en-029+m4 espeak:en-029+f2 espeak:en-gb-x-rp+m6 espeak:en-gb-x-rp+f4 espeak:en-us-nyc+m1 espeak:en-us-nyc+f3 espeak:en-gb-x-gbclan+m3 espeak:en-gb-x-gbclan+f2 espeak:en-gb-x-gbcwmd+m4 espeak:en-gb-x-gbcwmd+f4"
test_voices="espeak:en-us+f1 espeak:en-gb+m7 espeak:en-gb-x-gbclan+f5 espeak:en+m5 espeak:en-029+f1 espeak:en-gb-scotland+m7"
utts_per_train_voice=50
utts_per_test_voice=40
vocab_size=500
min_words=4
max_words=9
books="Gen1:1-50:26 Exo1:1-40:38 Psa1:1-150:6 Pro1:1-31:31 Mat1:1-28:20 Luk1:1-24:53 Joh1:1-21:25"
seed=0
nj=2
while [ $# -gt 1 ] && [[ "$1" == --* ]]; do
  name=${1#--}; name=${name//-/_}
  case $name in
    train_voices|test_voices|utts_per_train_voice|utts_per_test_voice|vocab_size|min_words|max_words|books|seed|nj)
      printf -v "$name" '%s' "$2" ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
[ $# -eq 1 ] || { sed -n '2,15p' "$0" >&2; exit 1; }
out=$1
die() { echo "make_tts_corpus.sh: ERROR: $*" >&2; exit 1; }
command -v bible >/dev/null || die "the sentence source 'bible' is missing: apt-get install bible-kjv"
command -v sox >/dev/null || die "sox is missing: apt-get install sox"
for v in $train_voices $test_voices; do
  case ${v%%:*} in
    espeak) command -v espeak-ng >/dev/null || die "voice $v needs espeak-ng: apt-get install espeak-ng" ;;
    flite) command -v flite >/dev/null || die "voice $v needs flite: apt-get install flite" ;;
    *) die "voice $v: engine must be espeak or flite" ;;
  esac
done
for t in $train_voices; do for u in $test_voices; do [ "$t" != "$u" ] || die "voice $t is both a train and a test voice"; done; done

sig="$train_voices|$test_voices|$utts_per_train_voice|$utts_per_test_voice|$vocab_size|$min_words|$max_words|$books|$seed"
if [ -f "$out/.done" ] && [ "$(cat "$out/.done")" = "$sig" ]; then
  echo "make_tts_corpus.sh: $out already made" >&2; exit 0
fi
mkdir -p "$out/local"

# Clauses: text joined, headers and verse numbers dropped, cut at . , ; : ? ! and ( ), lower-cased.
# shellcheck disable=SC2086
bible $books | grep -v -E '^[A-Z0-9][A-Za-z ]* [0-9]+$' | tr '\n' ' ' | tr -d '0-9' |
  tr '.,;:?!()' '\n\n\n\n\n\n\n\n' | tr 'A-Z' 'a-z' | sed "s/[^a-z' ]/ /g; s/  */ /g; s/^ //; s/ $//" \
  >"$out/local/all_clauses.txt"
# The vocabulary: the most frequent words (ties by spelling, so that it does not depend on sort's locale).
tr ' ' '\n' <"$out/local/all_clauses.txt" | grep . | LC_ALL=C sort | uniq -c |
  LC_ALL=C sort -k1,1nr -k2,2 | awk -v V="$vocab_size" 'NR <= V { print $2 }' >"$out/local/vocab.txt"
awk -v lo="$min_words" -v hi="$max_words" 'NR == FNR { keep[$1] = 1; next }
  { if (NF < lo || NF > hi || ($0 in seen)) next
    for (i = 1; i <= NF; i++) if (!($i in keep)) next
    seen[$0] = 1; print }' "$out/local/vocab.txt" "$out/local/all_clauses.txt" >"$out/local/clauses.txt"
n_clauses=$(wc -l <"$out/local/clauses.txt")
n_train=$(( $(wc -w <<<"$train_voices") * utts_per_train_voice ))
n_test=$(( $(wc -w <<<"$test_voices") * utts_per_test_voice ))
[ "$n_clauses" -ge $((n_train + n_test)) ] ||
  die "only $n_clauses distinct clauses of $min_words-$max_words words within the $vocab_size most frequent words; need $((n_train + n_test)) (raise --vocab-size or add --books)"
# Seeded shuffle; the first n_test clauses are the test sentences.
awk -v s="$seed" 'BEGIN { srand(s + 1) } { printf "%.12f\t%s\n", rand(), $0 }' "$out/local/clauses.txt" |
  sort -k1,1 | cut -f2- >"$out/local/shuffled.txt"

# One job line per utterance: set utt voice rate pitch text.
plan() {  # set voices per_voice first_line
  local set=$1 voices=$2 per=$3 line=$4 v k
  for v in $voices; do
    for ((k = 0; k < per; k++)); do
      local spk; spk=$(echo "${v#*:}" | tr '+_' '--')
      spk="${v%%:*}-$spk"
      printf '%s\t%s-%s-%04d\t%s\t%s\n' "$set" "$spk" "$set" "$k" "$v" "$(sed -n "${line}p" "$out/local/shuffled.txt")"
      line=$((line + 1))
    done
  done
}
{
  plan test "$test_voices" "$utts_per_test_voice" 1
  plan train "$train_voices" "$utts_per_train_voice" $((n_test + 1))
} | awk -F'\t' -v s="$seed" 'BEGIN { srand(s + 7) } { printf "%s\t%s\t%s\t%d\t%d\t%s\n", $1, $2, $3, 140 + int(rand() * 60), 30 + int(rand() * 40), $4 }' \
  >"$out/local/plan.tsv"

synth() {  # one plan line -> 16 kHz 16-bit wav
  local set utt voice rate pitch text
  IFS=$'\t' read -r set utt voice rate pitch text <<<"$1"
  local wav=$out/$set/wav/$utt.wav
  mkdir -p "$out/$set/wav"
  case ${voice%%:*} in
    # sox -R: repeatable dither (a random seed otherwise: the corpus would differ run to run).
    espeak) espeak-ng -v "${voice#*:}" -s "$rate" -p "$pitch" --stdout "$text" | sox -R -q -t wav - -r 16000 -b 16 "$wav.tmp.wav" gain -n -3 ;;
    flite) flite -voice "${voice#*:}" --setf duration_stretch="$(awk -v r="$rate" 'BEGIN { printf "%.3f", 170 / r }')" \
             --setf int_f0_target_mean="$((70 + pitch * 2))" -t "$text" -o "$wav.tmp.wav.raw.wav" &&
           sox -R -q "$wav.tmp.wav.raw.wav" -r 16000 -b 16 "$wav.tmp.wav" gain -n -3 && rm -f "$wav.tmp.wav.raw.wav" ;;
  esac
  mv "$wav.tmp.wav" "$wav"
}
export -f synth
export out
echo "make_tts_corpus.sh: synthesising $n_train train + $n_test test utterances ($n_clauses clauses available)" >&2
tr '\n' '\0' <"$out/local/plan.tsv" | xargs -0 -n 1 -P "$nj" bash -c 'synth "$0"'

for set in train test; do
  d=$out/$set
  awk -F'\t' -v set="$set" -v d="$(readlink -f "$d")" '$1 == set {
      split($3, v, ":"); spk = $2; sub("-" set "-[0-9]+$", "", spk)
      print $2, d "/wav/" $2 ".wav" > (d "/wav.scp.u"); print $2, $6 > (d "/text.u"); print $2, spk > (d "/utt2spk.u") }' \
    "$out/local/plan.tsv"
  for f in wav.scp text utt2spk; do LC_ALL=C sort "$d/$f.u" >"$d/$f"; rm "$d/$f.u"; done
  awk '{ a[$2] = a[$2] " " $1 } END { for (s in a) print s a[s] }' "$d/utt2spk" | LC_ALL=C sort >"$d/spk2utt"
done
printf '%s\n' "$sig" >"$out/.done"
echo "make_tts_corpus.sh: $out/train ($(wc -l <"$out/train/utt2spk") utts, $(wc -l <"$out/train/spk2utt") voices), $out/test ($(wc -l <"$out/test/utt2spk") utts, $(wc -l <"$out/test/spk2utt") voices)" >&2
