#!/usr/bin/env bash
# Reverberation through wav.scp pipes as Kaldi's feature extraction consumes them: one shell per
# utterance running the pipe's command (Kaldi's Input opens "cmd |" with popen(), i.e. /bin/sh -c;
# HARNESS=bash runs `bash -c` instead), one (outer) wav-reverberate process per utterance plus a
# nested one per noise.
# The same wav.scp (written once by reverberate-data with Kaldi's noise rules: an RIR of the room
# and the room's isotropic noise extended to the utterance) is run with tsrir's wav-reverberate and,
# when KALDI_ROOT is set, with Kaldi's (the pipes differ only in the program path). Prints wall and
# CPU (user+sys of everything the pipes start) per row; Kaldi's row says "absent" without KALDI_ROOT.
# The rows run interleaved, BLOCK (default 50) utterances at a time, so load that drifts during the
# run weighs on all of them alike. A last row runs `/bin/true` the same way: the floor any program
# pays in this harness (the shell and one exec).
#
# Usage: bench/augment/pipes_vs_kaldi.sh [<bin-dir>] [<num-utterances>]   (default build/bin, 1000)
# Signals (synthetic, sox): "speech" = pink noise amplitude-modulated at 4 Hz, 10 s, 16-bit 16 kHz;
# RIRs = 0.5 s decaying white noise after a direct-path impulse, 16-bit (Kaldi reads only PCM);
# isotropic noises = 30 s brown noise, 16-bit.
set -euo pipefail
BIN=$(cd "${1:-$(dirname "$0")/../../build/bin}" && pwd)
N=${2:-1000}
source "$(dirname "$0")/../peers/common.sh"  # machine_line
machine_line
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

# The rows run interleaved, a block of utterances at a time (tsrir, tsrir on Kaldi's form, Kaldi,
# then the next block), so that a machine whose load drifts during the run weighs on every row alike.
BLOCK=${BLOCK:-50}
HARNESS=${HARNESS:-sh}
case $HARNESS in sh | bash) ;; *) echo "HARNESS must be sh or bash" >&2; exit 2 ;; esac
mkdir -p data/floor
awk '{ print $1, "/bin/true |" }' data/tsrir_form/wav.scp > data/floor/wav.scp
rows=("tsrir|$BIN|data/tsrir_form" "tsrir on Kaldi's form|$BIN|data/kaldi_form" "floor: $HARNESS -c /bin/true|$BIN|data/floor")
have_kaldi=0
if [ -n "${KALDI_ROOT:-}" ] && [ -x "$KALDI_ROOT/src/featbin/wav-reverberate" ]; then
  rows+=("kaldi|$KALDI_ROOT/src/featbin|data/kaldi_form")
  have_kaldi=1
fi
for r in "${!rows[@]}"; do echo "0 0 0" > "row_$r.txt"; done
for ((first = 0; first < N; first += BLOCK)); do
  for r in "${!rows[@]}"; do
    IFS='|' read -r label dir data <<<"${rows[$r]}"
    sed -n "$((first + 1)),$((first + BLOCK))p" "$data/wav.scp" > block.scp
    t=$( { /usr/bin/time -f "%e %U %S" env PATH="$dir:$PATH" SCP=block.scp H="$HARNESS" bash -c '
        while read -r id rest; do "$H" -c "${rest% |}" > /dev/null || exit 1; done < "$SCP"' ; } 2>&1 | tail -1)
    read -r w0 c0 n0 < "row_$r.txt"
    set -- $t
    echo "$w0 $c0 $n0" | awk -v w="$1" -v u="$2" -v s="$3" -v b="$(wc -l < block.scp)" \
      '{ printf "%.3f %.3f %d\n", $1 + w, $2 + u + s, $3 + b }' > "row_$r.txt"
  done
done
for r in "${!rows[@]}"; do
  IFS='|' read -r label dir data <<<"${rows[$r]}"
  read -r w c n < "row_$r.txt"
  awk -v l="$label" -v n="$n" -v w="$w" -v c="$c" \
    'BEGIN { printf "| %-34s | %5d | %8.2f | %8.2f | %7.2f | %7.2f |\n", l, n, w, c, 1000 * w / n, 1000 * c / n }'
done
if [ $have_kaldi = 1 ]; then
  read -r tw tc tn < row_0.txt; read -r kw kc kn < row_3.txt
  read -r fw fc fn < row_2.txt
  awk -v tw="$tw" -v tc="$tc" -v kw="$kw" -v kc="$kc" -v fw="$fw" -v fc="$fc" \
    'BEGIN { printf "\ntsrir / Kaldi speed: %.2fx wall, %.2fx CPU", kw / tw, kc / tc;
             printf " (above the floor: %.2fx wall, %.2fx CPU)\n", (kw - fw) / (tw - fw), (kc - fc) / (tc - fc) }'
else
  echo "| kaldi                              | absent (KALDI_ROOT not set or no src/featbin/wav-reverberate) |"
fi
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
