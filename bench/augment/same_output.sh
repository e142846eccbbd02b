#!/usr/bin/env bash
# Do two builds of wav-reverberate write the same bytes? For a speed change that must not change the
# output (issue 35): runs both on the inputs of bench/peers/reverb_speed.sh and pipes_vs_kaldi.sh
# (10 s and 1 s 16-bit utterances, a 1 s int16 RIR of the reference room, 30 s and 10 s noises) under
# 7 option sets covering both --shift-output modes, nested noises (--additive-durations), two noises,
# --kaldi-compat, clipping (--volume=30), tiling (--duration=25) and the streamed path
# (--max-in-memory-duration=2), to a file and to stdout, and `cmp`s every pair.
#
# Usage: bench/augment/same_output.sh <wav-reverberate A> <wav-reverberate B> [<rir-simulate>]
#   (rir-simulate defaults to B's directory). Exit status 1 if any pair differs.
set -euo pipefail
A=$1
B=$2
SIM=${3:-$(dirname "$B")/rir-simulate}
d=$(mktemp -d "${TMPDIR:-/tmp}/tsrir_same_output.XXXXXX")
trap 'rm -rf "$d"' EXIT
echo "rir room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6" > "$d/room.txt"
"$SIM" --length=1.0 --format=int16 "$d/room.txt" "$d/rir" 2>/dev/null
sox -n -r 16000 -b 16 -c 1 "$d/noise.wav" synth 30 whitenoise vol 0.1
sox "$d/noise.wav" "$d/noise10.wav" trim 0 10
for u in 1 2 3; do sox -n -r 16000 -b 16 -c 1 "$d/u$u.wav" synth 10 pinknoise tremolo 4 90 vol 0.3 2>/dev/null; done
sox -n -r 16000 -b 16 -c 1 "$d/u1s.wav" synth 1 pinknoise tremolo 4 90 vol 0.3 2>/dev/null
rir=$d/rir/rir.wav
sets=("--shift-output=true --impulse-response=$rir --additive-signals=$d/noise.wav --snrs=10 --start-times=0"
      "--shift-output=false --impulse-response=$rir"
      "--impulse-response=$rir --additive-signals=$d/noise.wav,$d/noise10.wav --snrs=5,15 --start-times=0,2.5 --additive-durations=10,0"
      "--kaldi-compat=true --impulse-response=$rir --additive-signals=$d/noise.wav --snrs=0 --start-times=1"
      "--volume=30"
      "--normalize-output=false --duration=25 --impulse-response=$rir"
      "--max-in-memory-duration=2 --impulse-response=$rir --additive-signals=$d/noise.wav --snrs=10 --start-times=0")
n=0
differ=0
for s in "${sets[@]}"; do
  for u in u1 u2 u3 u1s; do
    # shellcheck disable=SC2086  # each set is a list of options
    "$A" $s "$d/$u.wav" "$d/a.wav" 2>/dev/null
    # shellcheck disable=SC2086
    "$B" $s "$d/$u.wav" "$d/b.wav" 2>/dev/null
    n=$((n + 1))
    cmp -s "$d/a.wav" "$d/b.wav" || { differ=$((differ + 1)); echo "differ (file): $s $u"; }
    # shellcheck disable=SC2086
    "$B" $s "$d/$u.wav" - 2>/dev/null | cmp -s - "$d/a.wav" || { differ=$((differ + 1)); echo "differ (stdout): $s $u"; }
  done
done
echo "$n option/input pairs, file and stdout: $differ differ"
[ "$differ" = 0 ]
