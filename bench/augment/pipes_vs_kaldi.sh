#!/usr/bin/env bash
# Reverberation through wav.scp pipes as Kaldi's feature extraction consumes them: one `bash -c`
# per utterance, one (outer) wav-reverberate process per utterance plus a nested one per noise.
# The same wav.scp (written once by reverberate-data with Kaldi's noise rules: an RIR of the room
# and the room's isotropic noise extended to the utterance) is run with tsrir's wav-reverberate and,
# when KALDI_ROOT is set, with Kaldi's (the pipes differ only in the program path). Prints wall and
# CPU (user+sys of everything the pipes start) per row; Kaldi's row says "absent" without KALDI_ROOT.
#
# Usage: bench/augment/pipes_vs_kaldi.sh [<bin-dir>] [<num-utterances>]   (default build/bin, 1000)
# Signals (synthetic, sox): "speech" = pink noise amplitude-modulated at 4 Hz, 10 s, 16-bit 16 kHz;
# RIRs = 0.5 s decaying white noise after a direct-path impulse, 16-bit (Kaldi reads only PCM);
# isotropic noises = 30 s brown noise, 16-bit.
set -euo pipefail
BIN=$(cd "${1:-$(dirname "$0")/../../build/bin}" && pwd)
N=${2:-1000}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/tsrir_pipes_vs_kaldi.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
mkdir -p audio rirs noise data/in
echo "generating $N x 10 s utterances, 8 RIRs in 4 rooms, 4 isotropic noises in $WORK ..." >&2
for r in 0 1 2 3 4 5 6 7; do
  sox -q -n -r 16000 -b 16 -c 1 rirs/tail$r.wav synth 0.5 whitenoise vol 0.15 fade l 0 0.5 0.45
  sox -q -n -r 16000 -b 16 -c 1 rirs/direct$r.wav synth 0.00006 square vol 0.9 pad 0.005 0.49494
  sox -q -m rirs/direct$r.wav rirs/tail$r.wav -b 16 rirs/rir$r.wav trim 0 0.5
  echo "--rir-id rir$r --room-id room$((r % 4)) rirs/rir$r.wav" >> rir_list
done
for n in 0 1 2 3; do
  sox -q -n -r 16000 -b 16 -c 1 noise/iso$n.wav synth 30 brownnoise gain -10
  echo "--noise-id iso$n --noise-type isotropic --room-linkage room$n noise/iso$n.wav" >> noise_list
done
gen() { for ((i = $1; i < N; i += 2)); do sox -q -n -r 16000 -b 16 -c 1 "audio/u$(printf %05d "$i").wav" synth 10 pinknoise tremolo 4 90 gain -8; done; }
gen 0 & gen 1 & wait
for ((i = 0; i < N; i++)); do
  id=$(printf %05d "$i")
  echo "spk$((i % 50))-u$id $WORK/audio/u$id.wav"
done | LC_ALL=C sort > data/in/wav.scp
awk '{split($1, a, "-"); print $1, a[1]}' data/in/wav.scp > data/in/utt2spk
awk '{print $1, 10}' data/in/wav.scp > data/in/reco2dur
# The same draws twice: Kaldi's pipe form (nested wav-reverberate per noise, program found through
# PATH) and tsrir's (its own program by path, the nested steps in that process).
"$BIN/reverberate-data" --rir-set-parameters rir_list --noise-set-parameters noise_list --random-seed 1 \
  --pipe-program wav-reverberate --pipe-dialect kaldi data/in data/kaldi_form 2>/dev/null
"$BIN/reverberate-data" --rir-set-parameters rir_list --noise-set-parameters noise_list --random-seed 1 \
  data/in data/tsrir_form 2>/dev/null

run_row() {  # <label> <dir holding wav-reverberate> <data dir>
  local label=$1 dir=$2 t
  t=$( { /usr/bin/time -f "%e %U %S" env PATH="$dir:$PATH" SCP="$3/wav.scp" bash -c '
      while read -r id rest; do bash -c "${rest% |} > /dev/null" || exit 1; done < "$SCP"' ; } 2>&1 | tail -1)
  set -- $t
  awk -v l="$label" -v n="$N" -v w="$1" -v u="$2" -v s="$3" \
    'BEGIN { printf "| %-34s | %5d | %8.2f | %8.2f | %7.2f | %7.2f |\n", l, n, w, u + s, 1000 * w / n, 1000 * (u + s) / n }'
  echo "$1 $(echo "$2 + $3" | bc)" > "row_${label// /_}.txt"
}
echo
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load before: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "Kaldi's form: $(head -1 data/kaldi_form/wav.scp | cut -d' ' -f2- | sed "s|$WORK/||g")"
echo "tsrir's form: $(head -1 data/tsrir_form/wav.scp | cut -d' ' -f2- | sed "s|$WORK/||g; s|$BIN/||g")"
echo
echo "| pipes                              | utts  | wall s   | CPU s    | wall ms/utt | CPU ms/utt |"
echo "|------------------------------------|-------|----------|----------|---------|---------|"
run_row tsrir "$BIN" data/tsrir_form
run_row "tsrir on Kaldi's form" "$BIN" data/kaldi_form
if [ -n "${KALDI_ROOT:-}" ] && [ -x "$KALDI_ROOT/src/featbin/wav-reverberate" ]; then
  run_row kaldi "$KALDI_ROOT/src/featbin" data/kaldi_form
  read -r tw tc < row_tsrir.txt; read -r kw kc < row_kaldi.txt
  awk -v tw="$tw" -v tc="$tc" -v kw="$kw" -v kc="$kc" \
    'BEGIN { printf "\ntsrir / Kaldi speed: %.2fx wall, %.2fx CPU\n", kw / tw, kc / tc }'
else
  echo "| kaldi                              | absent (KALDI_ROOT not set or no src/featbin/wav-reverberate) |"
fi
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
