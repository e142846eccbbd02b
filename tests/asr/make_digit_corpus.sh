#!/usr/bin/env bash
# Test data for the recogniser's learning test: spoken digit strings from espeak-ng (a formant
# synthesiser: independent of the features and model under test), as two Kaldi data dirs.
# Usage: make_digit_corpus.sh <out-dir> <seed> <train-utts> <test-utts>
# Voices (speaker = voice) are shared between train and test; test digit strings are drawn
# anew, so the test asks for the words, not memorised utterances.
set -euo pipefail
out=$1 seed=$2 n_train=$3 n_test=$4
command -v espeak-ng >/dev/null || { echo "make_digit_corpus.sh: espeak-ng is not installed" >&2; exit 1; }
words=(zero one two three four five six seven eight nine)
voices=(en-us+m3 en-gb+f2 en-us+m1 en+f4 en-gb-scotland+m2 en-us+f1)
RANDOM=$seed
make_set() {  # name count
  local dir=$out/$1 n=$2
  mkdir -p "$dir/wav"
  : >"$dir/wav.scp.u"; : >"$dir/text.u"; : >"$dir/utt2spk.u"
  for ((i = 0; i < n; i++)); do
    local v=${voices[$((i % ${#voices[@]}))]} len=$((3 + RANDOM % 3)) t=""
    for ((k = 0; k < len; k++)); do t+="${t:+ }${words[$((RANDOM % 10))]}"; done
    local spk=${v//+/-} rate=$((150 + RANDOM % 50)) pitch=$((35 + RANDOM % 30))
    local utt=$(printf '%s-%s-%04d' "$spk" "$1" "$i")
    espeak-ng -v "$v" -s "$rate" -p "$pitch" -w "$dir/wav/$utt.wav" "$t"
    echo "$utt $dir/wav/$utt.wav" >>"$dir/wav.scp.u"
    echo "$utt $t" >>"$dir/text.u"
    echo "$utt $spk" >>"$dir/utt2spk.u"
  done
  for f in wav.scp text utt2spk; do LC_ALL=C sort "$dir/$f.u" >"$dir/$f"; rm "$dir/$f.u"; done
  awk '{a[$2] = a[$2] " " $1} END {for (s in a) print s a[s]}' "$dir/utt2spk" | LC_ALL=C sort >"$dir/spk2utt"
}
make_set train "$n_train"
make_set test "$n_test"
