#!/usr/bin/env bash
# The inputs README.md's examples take for granted, written into the scratch directory <dir> (the
# examples' working directory) with the programs on PATH: real.scp / rooms000.txt (the 34 R3VIVAL
# RIRs of condition 000, docs/results/make_r3vival_inputs.sh), real/rir_list and real_train/rir_list, a Kaldi data dir
# data/clean (the 5 LibriSpeech utterances of ../shared/data, two of them as flac pipes), speech.wav,
# noise.wav (10 s of a real rain recording, 16 kHz mono), noise.scp, noise_list, rirs/ (two
# simulated rooms for the Python example). Without ../shared/data: stand-ins (rooms.txt written
# here, "real" RIRs simulated, espeak-ng speech, generated noise), said on stderr.
# usage: prepare_readme_inputs.sh <source dir> <scratch dir> <shared data dir>
set -euo pipefail
src=$1 d=$2 shared=$3
cd "$d"
mkdir -p data/clean real
if [ -d "$shared/rirs/r3vival" ] && [ -d "$shared/speech/librispeech" ] && [ -d "$shared/noise" ]; then
  "$src/docs/results/make_r3vival_inputs.sh" "$shared/rirs/r3vival" r3vival_inputs 2>/dev/null
  grep 'room-id=cond000' r3vival_inputs/rooms.txt >rooms000.txt
  awk 'NR == FNR {keep[$1] = 1; next} keep[$1]' rooms000.txt r3vival_inputs/rir.scp >real.scp
  ls="$shared/speech/librispeech"
  for f in "$ls"/*.wav; do u=$(basename "$f" .wav); echo "$u $f"; done >wav.scp.u
  for f in "$ls"/*.flac; do u=$(basename "$f" .flac); echo "$u flac -c -d -s $f |"; done >>wav.scp.u
  { tr '\t' ' ' <"$ls/trans.txt"; sed -n 's/^lbi-//p' "$ls/mini_librispeech_text.txt"; } >text.u
  sox "$ls/1089-134686-0001.wav" -b 16 speech.wav
  sox "$shared/noise/rain.ogg" -r 16000 -c 1 -b 16 noise.wav trim 0 10
else
  echo "prepare_readme_inputs: ../shared/data absent: stand-in rooms, RIRs, speech and noise" >&2
  for i in 1 2 3 4 5 6; do
    echo "standin$i room=9.7,5.5,2.7 src=$((1 + i)).2,1.5,1.35 mic=7.5,3.1,1.35 t60=0.7 room-id=cond000"
  done >rooms000.txt
  rir-simulate --model=gas+modes+air --length=auto rooms000.txt standin_real >/dev/null 2>&1
  cp standin_real/rir.scp real.scp
  cp rooms000.txt rooms.txt
  for i in 1 2 3; do
    u=spk$i-utt$i
    espeak-ng -w "data/$u.wav" "this is stand in sentence number $i for the examples"
    echo "$u $d/data/$u.wav" >>wav.scp.u
    echo "$u THIS IS STAND IN SENTENCE NUMBER $i FOR THE EXAMPLES" >>text.u
  done
  sox "data/spk1-utt1.wav" -r 16000 -b 16 speech.wav
  sox -n -r 16000 -b 16 noise.wav synth 10 pinknoise vol 0.1
fi
LC_ALL=C sort wav.scp.u >data/clean/wav.scp
# text only when every utterance has its transcript (one LibriSpeech flac has none here): a partial
# text is an invalid data dir, and the examples' data dirs need none (validate-data-dir --no-text).
LC_ALL=C sort text.u | awk 'NR == FNR {u[$1] = 1; next} u[$1]' data/clean/wav.scp - >text.covered
if [ "$(wc -l <text.covered)" -eq "$(wc -l <data/clean/wav.scp)" ]; then mv text.covered data/clean/text; else rm text.covered; fi
awk '{n = split($1, p, "-"); print $1, p[1] "-" p[2]}' data/clean/wav.scp >data/clean/utt2spk
awk '{a[$2] = a[$2] " " $1} END {for (s in a) print s a[s]}' data/clean/utt2spk | LC_ALL=C sort >data/clean/spk2utt
rm -f wav.scp.u text.u
awk '{print "--rir-id " $1 " --room-id r3vival " $2}' real.scp >real/rir_list
# real_train/rir_list: the demo's training RIRs in rir-perturb's examples; here the same real RIRs.
mkdir -p real_train
cp real/rir_list real_train/rir_list
echo "rain $d/noise.wav" >noise.scp
{ echo "--noise-id rain --noise-type point-source --bg-fg-type background $d/noise.wav"
  echo "--noise-id rain_iso --noise-type isotropic --bg-fg-type background --room-linkage r3vival $d/noise.wav"; } >noise_list
printf 'r1 room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.5\nr2 room=8,6,3 src=2,2,1.5 mic=6,4,1.2 t60=0.8\n' >python_rooms.txt
rir-simulate --length=auto python_rooms.txt rirs >/dev/null 2>&1
mkdir -p tests/asr examples
cp "$src/tests/asr/make_digit_corpus.sh" tests/asr/
