#!/usr/bin/env bash
# Scale and memory under hostile sizes: a 2-hour utterance through wav-reverberate and
# reverberate-data (peak RSS must stay a small multiple of the audio), and 10^5-line lists through
# reverberate-data, rir-metrics and rir-simulate. Prints one table row per case.
#
#   bench/robustness/run_bench.sh [BIN_DIR [HOURS [LIST_LINES [METRICS_RIRS]]]]
#                                                    (default build/bin 2 100000 10000)
# rir-metrics really measures every RIR of its list (~5 ms each), so its list is shorter by default.
#
# Inputs are generated under $WORK (default /tmp/tsrir_robust_bench, ~0.5 GB for 2 h) and removed
# afterwards. Needs python3 (to write the long WAV quickly) and GNU time (/usr/bin/time).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
hours=${2:-2}
lines=${3:-100000}
metrics_rirs=${4:-10000}
work=${WORK:-/tmp/tsrir_robust_bench}
rm -rf "$work"
mkdir -p "$work/data" "$work/big"
trap 'rm -rf "$work"' EXIT

python3 - "$work" "$hours" "$lines" "$metrics_rirs" <<'PY'
import math, os, random, struct, sys
work, hours, lines, metrics_rirs = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
def header(n):
    d = 2 * n
    return b'RIFF' + struct.pack('<I', 36 + d) + b'WAVEfmt ' + struct.pack('<IHHIIHH', 16, 1, 1, 16000, 32000, 2, 16) + b'data' + struct.pack('<I', d)
# One second of a 440 Hz tone with a slow amplitude pattern, repeated: fast to write.
sec = b''.join(struct.pack('<h', int(6000 * math.sin(2 * math.pi * 440 * i / 16000))) for i in range(16000))
n = int(hours * 3600 * 16000)
with open(os.path.join(work, 'long.wav'), 'wb') as f:
    f.write(header(n))
    for _ in range(n // 16000):
        f.write(sec)
random.seed(1)
rir = [0] * 40 + [20000] + [int(3000 * 10 ** (-3 * (i / 16000) / 0.5) * random.gauss(0, 1)) for i in range(8000)]
with open(os.path.join(work, 'rir.wav'), 'wb') as f:
    f.write(header(len(rir)) + b''.join(struct.pack('<h', max(-32767, min(32767, v))) for v in rir))
with open(os.path.join(work, 'short.wav'), 'wb') as f:
    f.write(header(16000) + sec)
d = os.path.join(work, 'data')
open(os.path.join(d, 'wav.scp'), 'w').write('spk1-long %s/long.wav\n' % work)
open(os.path.join(d, 'utt2spk'), 'w').write('spk1-long spk1\n')
open(os.path.join(d, 'spk2utt'), 'w').write('spk1 spk1-long\n')
open(os.path.join(work, 'rir.scp'), 'w').write('r1 %s/rir.wav\n' % work)
b = os.path.join(work, 'big')
with open(os.path.join(b, 'wav.scp'), 'w') as w, open(os.path.join(b, 'utt2spk'), 'w') as u:
    for i in range(lines):
        w.write('spk%04d-utt%07d %s/short.wav\n' % (i // 1000, i, work))
        u.write('spk%04d-utt%07d spk%04d\n' % (i // 1000, i, i // 1000))
with open(os.path.join(work, 'big_rir.scp'), 'w') as f:
    for i in range(metrics_rirs):
        f.write('r%07d %s/rir.wav\n' % (i, work))
with open(os.path.join(work, 'rooms.txt'), 'w') as f:
    for i in range(lines):
        f.write('r%07d room=5,4,3 src=1,1,1 mic=3,2,1.5 t60=0.4\n' % i)
    f.write('r0000005 room=5,4,3 src=1,1,1 mic=3,2,1.5 t60=0.4\n')
PY

audio_mb=$(( $(stat -c %s "$work/long.wav") * 2 / 1000000 ))  # as float32 samples in memory
printf '%-52s %8s %10s %8s\n' case seconds peak_MB result
run() {
  local name=$1 rc=0 secs kb
  shift
  /usr/bin/time -o "$work/time" -f '%e %M' "$@" >/dev/null 2>"$work/err" || rc=$?
  read -r secs kb < <(tail -1 "$work/time")
  printf '%-52s %8s %10s %8s\n' "$name" "$secs" "$(( kb / 1024 ))" "exit=$rc"
  [ "$rc" = 0 ] || tail -1 "$work/err" | cut -c1-160
}
echo "# the ${hours} h utterance is ${audio_mb} MB as float samples"
run "wav-reverberate, ${hours} h utterance, 0.5 s RIR" "$bin/wav-reverberate" --print-args=false \
  --impulse-response="$work/rir.wav" "$work/long.wav" "$work/long_rvb.wav"
run "reverberate-data --write-wavs, ${hours} h utterance" "$bin/reverberate-data" --rir-set-parameters "$work/rir.scp" \
  --random-seed=1 --write-wavs="$work/wavs" "$work/data" "$work/data_rvb"
cp "$work/data/spk2utt" "$work/big/spk2utt" 2>/dev/null || true
python3 - "$work/big" <<'PY'
import collections, sys
spk = collections.OrderedDict()
for line in open(sys.argv[1] + '/utt2spk'):
    u, s = line.split()
    spk.setdefault(s, []).append(u)
open(sys.argv[1] + '/spk2utt', 'w').write(''.join('%s %s\n' % (s, ' '.join(us)) for s, us in spk.items()))
PY
run "reverberate-data (pipes), ${lines}-line wav.scp" "$bin/reverberate-data" --rir-set-parameters "$work/rir.scp" \
  --random-seed=1 "$work/big" "$work/big_rvb"
run "rir-metrics, ${metrics_rirs}-line scp" "$bin/rir-metrics" --num-threads="$(nproc)" "$work/big_rir.scp"
run "rir-simulate, ${lines}-line room list, bad last line" "$bin/rir-simulate" "$work/rooms.txt" "$work/sim"
