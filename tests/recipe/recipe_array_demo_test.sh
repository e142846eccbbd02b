#!/usr/bin/env bash
# egs/librispeech_farfield/local/array_demo.sh at a tiny size (issue 33): 2 sources of the R3VIVAL
# layout, an 8-microphone circular array, 2 short utterances (sox noise, 0.6 s). Checks what the
# demo promises, each against a value known without the simulator: 8-channel RIRs per source, 8-channel
# wavs, one per-channel entry per microphone with --rir-channel, Kaldi's reco2file_and_channel,
# both data dirs valid, and the figure's files. Also: the direct sound reaches the 8 microphones in
# the order the geometry gives (the microphone nearest the source first; mics 4 and 6 are 0.7
# sample later than 5, so the peaks are refined to a fraction of a sample), from the WAV itself.
# Env: TSRIR_BIN = the directory of the built programs (set by CTest).
set -uo pipefail
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else fail "$what"; fi; }
here=$(cd "$(dirname "$0")" && pwd)
recipe=$(cd "$here/../../egs/librispeech_farfield" && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
export PATH=$TSRIR_BIN:$PATH LC_ALL=C
command -v sox >/dev/null || { echo "SKIP: sox is not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$recipe"

mkdir -p "$tmp/speech"
for u in 1 2; do
  sox -R -n -r 16000 -b 16 "$tmp/spk$u-u$u.wav" synth 0.6 pinknoise vol 0.2
  echo "spk$u-u$u $tmp/spk$u-u$u.wav" >>"$tmp/speech/wav.scp"
  echo "spk$u-u$u spk$u" >>"$tmp/speech/utt2spk"
  echo "spk$u-u$u HELLO WORLD" >>"$tmp/speech/text"
done
out=$tmp/out
local/array_demo.sh --sources "S000-150 S090-150" --length 0.3 "$tmp/speech" "$out" >"$tmp/log" 2>&1 ||
  { cat "$tmp/log"; fail "array_demo.sh exits 0"; exit 1; }

channels() { soxi -c "$1" 2>/dev/null || sox --i -c "$1"; }
check "2 RIRs of 8 channels" test "$(for f in "$out"/rirs/r3v050-S000-150.wav "$out"/rirs/r3v050-S090-150.wav; do channels "$f"; done | tr '\n' ' ')" = "8 8 "
check "8-channel far-field wavs" test "$(for f in "$out"/wavs_multichannel/*.wav; do channels "$f"; done | sort -u)" = "8"
check "multichannel data dir: 2 recordings" test "$(wc -l <"$out/data_multichannel/wav.scp")" -eq 2
check "per-channel data dir: 16 recordings" test "$(wc -l <"$out/data_per_channel/wav.scp")" -eq 16
check "per-channel ids .CH1-.CH8, --rir-channel 0-7" \
  test "$(awk '{split($1, a, ".CH"); for (i = 2; i <= NF; i++) if ($i ~ /^--rir-channel=/) { split($i, b, "="); if (b[2] != a[2] - 1) bad = 1 }} END {print bad + 0}' "$out/data_per_channel/wav.scp")" = 0
check "reco2file_and_channel: <id> <id> A" \
  test "$(awk '$1 != $2 || $3 != "A"' "$out/data_per_channel/reco2file_and_channel" | wc -l)" -eq 0
for d in data_multichannel data_per_channel; do
  check "$d valid" validate-data-dir --no-feats "$out/$d"
done
check "figure written" test -s "$out/rirs.svg"
check "figure has 16 traces (8 early, 8 levels)" test "$(grep -c '<polyline' "$out/rirs.svg")" -eq 16
# Source S000-150 at (4.70, 2.75), array centre (6.20, 2.75), microphone k at azimuth 45k degrees:
# microphone 5 (azimuth 180, towards the source) hears it first, microphone 1 (azimuth 0) last.
order=$(python3 - "$out/rirs/r3v050-S000-150.wav" "$recipe/local" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
from plot_array_rirs import read_wav
rate, channels = read_wav(sys.argv[1])
def arrival(c):  # the direct sound's peak, refined by a parabola through its 3 samples
    i = max(range(1, len(c) - 1), key=lambda j: abs(c[j]))
    a, b, d = abs(c[i - 1]), abs(c[i]), abs(c[i + 1])
    return i + 0.5 * (a - d) / (a - 2 * b + d)
peaks = [arrival(c) for c in channels]
print(min(range(8), key=lambda k: peaks[k]) + 1, max(range(8), key=lambda k: peaks[k]) + 1)
PY
)
check "direct sound first at microphone 5, last at microphone 1 (got '$order')" test "$order" = "5 1"

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "all passed"
