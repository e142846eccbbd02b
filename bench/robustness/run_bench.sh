#!/usr/bin/env bash
# Scale and memory under hostile sizes: a 2-hour utterance through wav-reverberate and
# reverberate-data (0.5 s RIR; and 1 s RIR plus a looped 7 s noise, the case whose memory must not
# grow with the utterance: each such row is checked against RSS_LIMIT_MB, default 150, and the
# streamed wav-reverberate output is compared byte for byte with the in-memory path's), and
# 10^5-line lists through reverberate-data, rir-metrics and rir-simulate. Prints one table row per
# case and exits 1 if a check failed (the rir-simulate row's exit=1 is expected: its list's last
# line repeats an id). COMPARE=0 skips the in-memory reference run (~1.5 GB).
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
# 1 s RIR (T60 0.6 s) and a 7 s noise (looped over the utterance from an offset).
rir1 = [0] * 40 + [20000] + [int(3000 * 10 ** (-3 * (i / 16000) / 0.6) * random.gauss(0, 1)) for i in range(15959)]
with open(os.path.join(work, 'rir1s.wav'), 'wb') as f:
    f.write(header(len(rir1)) + b''.join(struct.pack('<h', max(-32767, min(32767, v))) for v in rir1))
noise = [int(2000 * random.gauss(0, 1)) for i in range(7 * 16000)]
with open(os.path.join(work, 'noise.wav'), 'wb') as f:
    f.write(header(len(noise)) + b''.join(struct.pack('<h', max(-32767, min(32767, v))) for v in noise))
with open(os.path.join(work, 'short.wav'), 'wb') as f:
    f.write(header(16000) + sec)
d = os.path.join(work, 'data')
open(os.path.join(d, 'wav.scp'), 'w').write('spk1-long %s/long.wav\n' % work)
open(os.path.join(d, 'utt2spk'), 'w').write('spk1-long spk1\n')
open(os.path.join(d, 'spk2utt'), 'w').write('spk1 spk1-long\n')
open(os.path.join(work, 'rir.scp'), 'w').write('r1 %s/rir.wav\n' % work)
open(os.path.join(work, 'rir1s.scp'), 'w').write('r1 %s/rir1s.wav\n' % work)
open(os.path.join(work, 'noise_list'), 'w').write('--noise-id n1 --noise-type point-source %s/noise.wav\n' % work)
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
rss_limit_mb=${RSS_LIMIT_MB:-150}
failed=0
printf '%-58s %8s %10s %8s\n' case seconds peak_MB result
# run [--rss-check] NAME COMMAND...: one row; --rss-check flags a peak RSS above RSS_LIMIT_MB.
run() {
  local check=0 rc=0 secs kb note
  if [ "$1" = --rss-check ]; then check=1; shift; fi
  local name=$1
  shift
  /usr/bin/time -o "$work/time" -f '%e %M' "$@" >/dev/null 2>"$work/err" || rc=$?
  read -r secs kb < <(tail -1 "$work/time")
  note="exit=$rc"
  if [ "$check" = 1 ]; then
    [ "$rc" = 0 ] || failed=1
    if [ $(( kb / 1024 )) -gt "$rss_limit_mb" ]; then note="$note,RSS>${rss_limit_mb}MB"; failed=1; fi
  fi
  printf '%-58s %8s %10s %8s\n' "$name" "$secs" "$(( kb / 1024 ))" "$note"
  [ "$rc" = 0 ] || tail -1 "$work/err" | cut -c1-160
}
echo "# the ${hours} h utterance is ${audio_mb} MB as float samples"
run "wav-reverberate, ${hours} h utterance, 0.5 s RIR" "$bin/wav-reverberate" --print-args=false \
  --impulse-response="$work/rir.wav" "$work/long.wav" "$work/long_rvb.wav"
run "reverberate-data --write-wavs, ${hours} h utterance" "$bin/reverberate-data" --rir-set-parameters "$work/rir.scp" \
  --random-seed=1 --write-wavs="$work/wavs" "$work/data" "$work/data_rvb"
rm -rf "$work/wavs" "$work/data_rvb" "$work/long_rvb.wav"
noisy=(--impulse-response="$work/rir1s.wav" --additive-signals="$work/noise.wav" --snrs=10 --start-times=0
       --additive-offsets=2.5 --loop-additive-signals=true)
run --rss-check "wav-reverberate, ${hours} h, 1 s RIR, looped noise" "$bin/wav-reverberate" --print-args=false \
  "${noisy[@]}" "$work/long.wav" "$work/long_noisy.wav"
if [ "${COMPARE:-1}" = 1 ]; then
  run "  the same in memory (--max-in-memory-duration=1e9)" "$bin/wav-reverberate" --print-args=false \
    --max-in-memory-duration=1e9 "${noisy[@]}" "$work/long.wav" "$work/long_noisy_ref.wav"
  if cmp -s "$work/long_noisy.wav" "$work/long_noisy_ref.wav"; then same=identical; else same=DIFFERENT; failed=1; fi
  printf '%-58s %8s %10s %8s\n' "  streamed vs in-memory output" - - "$same"
  rm -f "$work/long_noisy_ref.wav"
fi
rm -f "$work/long_noisy.wav"
run --rss-check "reverberate-data --write-wavs, ${hours} h, 1 s RIR, looped noise" "$bin/reverberate-data" \
  --rir-set-parameters "$work/rir1s.scp" --noise-set-parameters "$work/noise_list" --random-seed=1 \
  --write-wavs="$work/wavs" "$work/data" "$work/data_rvb"
rm -rf "$work/wavs" "$work/data_rvb"
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
run "rir-metrics, ${metrics_rirs}-line scp" "$bin/rir-metrics" --num-threads="$("$root/utils/cores")" "$work/big_rir.scp"
run "rir-simulate, ${lines}-line room list, bad last line" "$bin/rir-simulate" "$work/rooms.txt" "$work/sim"
[ "$failed" = 0 ] || { echo "# a check failed (exit status, RSS limit or output comparison)"; exit 1; }
