#!/bin/bash
# reverberate-data --write-wavs vs Kaldi's steps/data/reverberate_data_dir.py + running its wav.scp
# pipes (Kaldi's wav-reverberate) to files, same data dir and RIR list, RIRs only (no noise: Kaldi
# reverberates point-source noises, tsrir adds noise unreverberated, so only the RIR part is the
# same work) (issue 20).
#   bench/peers/datadir_speed.sh [utterances (40)] [utterance s (10)]
# Inputs generated here: 16 kHz 16-bit utterances (sox pink noise, 4 Hz modulation), 5 int16 1 s
# RIRs of the reference room; reco2dur is given to both (Kaldi's script would otherwise run
# wav-to-duration). Times: CPU (user+sys of everything started) and wall, whole job.
set -euo pipefail
source "$(dirname "$0")/common.sh"
n=${1:-40}; dur=${2:-10}
need_tsrir reverberate-data wav-reverberate rir-simulate
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
mkdir -p "$tmp/data/clean"
for i in $(seq -w 1 "$n"); do
  sox -n -r 16000 -b 16 -c 1 "$tmp/u$i.wav" synth "$dur" pinknoise tremolo 4 90 vol 0.3 2>/dev/null
  echo "utt$i $tmp/u$i.wav" >> "$tmp/data/clean/wav.scp"
  echo "utt$i spk$i" >> "$tmp/data/clean/utt2spk"
  echo "spk$i utt$i" >> "$tmp/data/clean/spk2utt"
  echo "utt$i $dur" >> "$tmp/data/clean/reco2dur"
done
for k in 1 2 3 4 5; do echo "r$k room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.$((k + 3))"; done > "$tmp/rooms.txt"
"$TSRIR_BIN/rir-simulate" --length=1.0 --format=int16 "$tmp/rooms.txt" "$tmp/rirs" 2>/dev/null
echo
echo "## Reverberated data dir with wavs on disk: $n utterances x $dur s, 5 RIRs (1 s), no noise, one core"
echo "| pipeline | wall ms/utt | CPU ms/utt | CPU: Kaldi / tsrir |"
echo "|---|---|---|---|"
read -r w c < <(time_cmd "$TSRIR_BIN/reverberate-data" --rir-set-parameters "1.0, $tmp/rirs/rir_list" \
  --num-replications 1 --prefix rvb --random-seed 1 --write-wavs "$tmp/tsrir_wavs" --num-threads 1 "$tmp/data/clean" "$tmp/data/tsrir_rvb")
ours=$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}')
echo "| tsrir reverberate-data --write-wavs --num-threads 1 | $(awk -v c="$w" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}') | $ours | |"
if have_kaldi; then
  cat > "$tmp/kaldi_job.sh" <<JOB
set -e
cd "$tmp/egs"
export PATH="$KALDI_ROOT/src/featbin:\$PATH"
python3 steps/data/reverberate_data_dir.py --rir-set-parameters "1.0, $tmp/rirs/rir_list" \
  --num-replications 1 --prefix rvb --random-seed 1 --source-sampling-rate 16000 \
  "$tmp/data/clean" "$tmp/data/kaldi_rvb" >/dev/null 2>&1
mkdir -p "$tmp/kaldi_wavs"
while read -r id cmd; do bash -c "\${cmd%|} > $tmp/kaldi_wavs/\$id.wav" 2>/dev/null; done < "$tmp/data/kaldi_rvb/wav.scp"
JOB
  mkdir -p "$tmp/egs"; ln -s "$KALDI_ROOT/egs/wsj/s5/steps" "$tmp/egs/steps"; ln -s "$KALDI_ROOT/egs/wsj/s5/utils" "$tmp/egs/utils"
  read -r w c < <(time_cmd bash "$tmp/kaldi_job.sh")
  k=$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}')
  echo "| Kaldi reverberate_data_dir.py + its wav.scp pipes run to files | $(awk -v c="$w" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}') | $k | $(ratio "$ours" "$k") |"
  echo "files written: tsrir $(ls "$tmp/tsrir_wavs" | wc -l), Kaldi $(find "$tmp/kaldi_wavs" -name '*.wav' -size +1k | wc -l)"
else
  echo "| Kaldi reverberate_data_dir.py + its wav.scp pipes run to files | absent | absent | - |"
fi
echo "Load after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
