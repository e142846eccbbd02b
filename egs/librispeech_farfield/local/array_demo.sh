#!/usr/bin/env bash
# Microphone-array far-field data from the demo's R3VIVAL room (issue 33), outside run.sh's stages
# (so the demo's time does not grow). From conf/r3vival_layout.txt: the room's size, the array's
# centre at the omni microphone's position, the measured T30s of one absorption condition, and the
# chosen sources. It writes into <out-dir>:
#   circular.txt       the array: --num-mics microphones on a horizontal circle of --radius-m
#   room_list          one rir-simulate line per source (array=circular.txt)
#   rirs/              rir-simulate's multichannel RIRs (channel c = microphone c), rir.scp, rir_list
#   data_multichannel/ reverberate-data --multi-channel-output=true: one multichannel recording per
#                      utterance (for a beamformer or a multichannel front end)
#   data_per_channel/  reverberate-data --split-channels=true: one recording per channel (<id>.CH<c>),
#                      the per-channel form (CHiME-4-style training on every channel)
#   wavs_multichannel/ the multichannel recordings' wavs (--write-wavs)
#   rirs.svg, rirs.png the first source's RIRs, every channel (rirs.png where rsvg-convert exists)
# Both data dirs are checked with local/check_data_dir.sh (validate-data-dir, Kaldi's rules).
#   local/array_demo.sh [options] <speech-data-dir> <out-dir>
# e.g. (after stage 1 of run.sh --demo)  local/array_demo.sh data/demo/speech/test_clean exp/array_demo
set -euo pipefail

condition=050                         # R3VIVAL absorption condition (the layout's T30s)
sources="S000-150 S090-150 S180-200"  # source ids of the layout
num_mics=8
radius_m=0.05
length=0.6                            # RIR length, s
model=gas                             # rir-simulate --model
seed=1
layout=conf/r3vival_layout.txt
help_message="Usage: $0 [--condition 050] [--sources 'S000-150 ...'] [--num-mics 8] [--radius-m 0.05]
  [--length 0.6] [--model gas] [--seed N] <speech-data-dir> <out-dir>"
. ./local/parse_options.sh
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
speech=$1
out=$2
for p in rir-simulate reverberate-data validate-data-dir; do
  command -v "$p" >/dev/null || { echo "$0: $p is not on PATH (build the toolkit, source path.sh)" >&2; exit 1; }
done
[ -f "$layout" ] || { echo "$0: missing $layout" >&2; exit 1; }
[ -f "$speech/wav.scp" ] || { echo "$0: $speech/wav.scp: no such file" >&2; exit 1; }
awk -v c="$condition" '$1 == "condition" && $2 == c {found = 1} END {exit !found}' "$layout" ||
  { echo "$0: $layout has no condition '$condition'" >&2; exit 1; }

mkdir -p "$out"
out=$(cd "$out" && pwd)
printf 'circular n=%s radius_m=%s\n' "$num_mics" "$radius_m" >"$out/circular.txt"
read -r _ lx ly lz < <(grep '^room ' "$layout")
read -r _ mx my mz < <(grep '^mic ' "$layout")
# The measured T30s per band (62.5 Hz = 125 Hz, 8 kHz = 4 kHz), as make_demo_data.sh's stand-ins.
t60=$(awk -v c="$condition" '$1 == "condition" && $2 == c {printf "%s,%s,%s,%s,%s,%s,%s,%s", $3,$3,$4,$5,$6,$7,$8,$8}' "$layout")
for s in $sources; do
  line=$(awk -v s="$s" '$1 == "source" && $2 == s' "$layout")
  [ -n "$line" ] || { echo "$0: $layout has no source '$s'" >&2; exit 1; }
  read -r _ _ sx sy sz <<<"$line"
  echo "r3v$condition-$s room=$lx,$ly,$lz src=$sx,$sy,$sz mic=$mx,$my,$mz array=$out/circular.txt t60=$t60 room-id=r3vival-a$condition"
done >"$out/room_list"

echo "$0: simulating $(wc -l <"$out/room_list") array RIRs ($num_mics microphones, radius $radius_m m)" >&2
rir-simulate --model="$model" --seed="$seed" --fs=16000 --length="$length" --format=float --overwrite=true \
  "$out/room_list" "$out/rirs"

echo "$0: far-field data dirs from $speech" >&2
reverberate-data --rir-set-parameters "$out/rirs/rir_list" --multi-channel-output=true --random-seed "$seed" \
  --write-wavs "$out/wavs_multichannel" --overwrite=true "$speech" "$out/data_multichannel"
reverberate-data --rir-set-parameters "$out/rirs/rir_list" --split-channels=true --random-seed "$seed" \
  --overwrite=true "$speech" "$out/data_per_channel"
for d in data_multichannel data_per_channel; do
  local/check_data_dir.sh "$out/$d"
done

first=$(head -n 1 "$out/room_list" | cut -d' ' -f1)
python3 local/plot_array_rirs.py --title "R3VIVAL room (condition $condition), source $first: $num_mics-mic circular array, r = $radius_m m" \
  "$out/rirs/$first.wav" "$out/rirs.svg"
if command -v rsvg-convert >/dev/null; then
  rsvg-convert -o "$out/rirs.png.tmp" "$out/rirs.svg" && mv "$out/rirs.png.tmp" "$out/rirs.png"
fi
echo "$0: done: $out/data_multichannel ($(wc -l <"$out/data_multichannel/wav.scp") recordings), $out/data_per_channel ($(wc -l <"$out/data_per_channel/wav.scp") recordings), $out/rirs.svg" >&2
