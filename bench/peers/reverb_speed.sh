#!/bin/bash
# wav-reverberate (tsrir) vs Kaldi's wav-reverberate, file to file, same inputs and options (issue 20).
#   bench/peers/reverb_speed.sh [utterances (200)] [utterance s (10)]
# Inputs: generated here (sox): 16 kHz 16-bit utterances (pink noise, 4 Hz amplitude modulation),
# one 1.0 s RIR of the reference room written as int16 (Kaldi reads only PCM RIRs), one 30 s noise.
# Each utterance is one process per tool: --shift-output=true --impulse-response=rir.wav
# --additive-signals=noise.wav --snrs=10 --start-times=0 in.wav out.wav. Times: the whole
# process (start, reading, FFT planning, writing), CPU = user+sys, over all utterances.
# Also prints how far the two outputs are apart (the same work was done). CPU time of processes this
# short is sampled by the kernel's tick: 200 utterances keep the sums within a few per cent (20 moved
# the ratio between 4.0x and 5.6x from one run to the next).
set -euo pipefail
source "$(dirname "$0")/common.sh"
n=${1:-200}; dur=${2:-10}
need_tsrir wav-reverberate rir-simulate
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
echo "rir room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6" > "$tmp/room.txt"
"$TSRIR_BIN/rir-simulate" --length=1.0 --format=int16 "$tmp/room.txt" "$tmp/rir" 2>/dev/null
sox -n -r 16000 -b 16 -c 1 "$tmp/noise.wav" synth 30 whitenoise vol 0.1
for i in $(seq -w 1 "$n"); do
  sox -n -r 16000 -b 16 -c 1 "$tmp/u$i.wav" synth "$dur" pinknoise tremolo 4 90 vol 0.3 2>/dev/null
done
opts=(--shift-output=true --impulse-response="$tmp/rir/rir.wav" --additive-signals="$tmp/noise.wav" --snrs=10 --start-times=0)
run_all() {  # $1 = binary, $2 = out prefix
  for i in $(seq -w 1 "$n"); do "$1" "${opts[@]}" "$tmp/u$i.wav" "$tmp/$2$i.wav" 2>/dev/null; done
}
export -f run_all; export tmp n; 
echo
echo "## wav-reverberate file to file: $n utterances x $dur s, 1 s RIR + noise at 10 dB, one process per utterance"
echo "| program | wall ms/utt | CPU ms/utt | CPU: Kaldi / tsrir |"
echo "|---|---|---|---|"
read -r w c < <(time_cmd bash -c "$(declare -p opts); $(declare -f run_all); run_all '$TSRIR_BIN/wav-reverberate' t")
ours_c=$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}')
echo "| tsrir wav-reverberate | $(awk -v c="$w" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}') | $ours_c | |"
if have_kaldi; then
  read -r w c < <(time_cmd bash -c "$(declare -p opts); $(declare -f run_all); run_all '$KALDI_ROOT/src/featbin/wav-reverberate' k")
  k_c=$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}')
  echo "| Kaldi wav-reverberate | $(awk -v c="$w" -v n="$n" 'BEGIN{printf "%.2f", 1000*c/n}') | $k_c | $(ratio "$ours_c" "$k_c") |"
  "$PRA_PYTHON" - "$tmp" "$n" <<'PY'
import sys, numpy as np, scipy.io.wavfile as w
d, n = sys.argv[1], int(sys.argv[2])
worst = -1e9
for i in range(1, n + 1):
    a = w.read("%s/t%0*d.wav" % (d, len(str(n)), i))[1].astype(float)
    b = w.read("%s/k%0*d.wav" % (d, len(str(n)), i))[1].astype(float)
    m = min(len(a), len(b))
    worst = max(worst, 10 * np.log10(np.sum((a[:m] - b[:m]) ** 2) / np.sum(b[:m] ** 2) + 1e-30))
print("outputs: worst difference energy tsrir vs Kaldi %.1f dB re Kaldi's output (same lengths: %s)" % (worst, len(a) == len(b)))
PY
else
  echo "| Kaldi wav-reverberate | absent | absent | - |"
fi
echo "Load after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
