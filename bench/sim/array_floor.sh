#!/bin/bash
# Issue 33 item 5's "8 microphones <= 2x one microphone": how far below 2x any rendering of this model
# can go. perf profiles rir-simulate (gas, 1.0 s, 16 kHz, float WAVs) on one microphone and on the
# 8-microphone circular array of bench/sim/array_speed.sh at the same positions, and prices the work
# that every microphone needs whatever the rendering, because each has its own image delays and its
# own tail noise:
#   - its image arrivals (distances and band amplitudes: image_arrivals) and their band-limited
#     fractional-delay taps (add_arrival_impulses), measured in the 8-mic run, where the image lattice
#     is already shared;
#   - its fresh white noise (Rng::fill_uniform), also from the 8-mic run;
#   - one real FFT of the RIR's length, the least a band-shaped noise of that length costs (today a
#     microphone takes 9: 8 band spectra and one inverse); one ninth of FFTW's share of the 1-mic run.
# With T1 the 1-mic CPU time per position and P that per-microphone floor, 8 microphones cost at least
# T1 + 7 P (everything else shared, for free), so the ratio is at least 1 + 7 P / T1.
#   bench/sim/array_floor.sh [bin-dir] [positions]
set -euo pipefail
bin=$(cd "${1:-build/bin}" && pwd)
n=${2:-1000}
command -v perf >/dev/null || { echo "array_floor: needs perf (Debian's linux-perf)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
freq=4999
# shellcheck source=bench/sim/array_lists.sh
source "$(dirname "$0")/array_lists.sh"
write_array_lists "$tmp" "$n"
cd "$tmp"
for list in one eight; do
  perf record -q -F "$freq" -o "$list.data" "$bin/rir-simulate" --model=gas --format=float --length=1.0 \
    --num-threads=1 "$list.txt" "out_$list" 2>/dev/null
  perf report -i "$list.data" --no-children --sort symbol 2>/dev/null | grep -v '^#' | grep '%' > "$list.shares"
done
# CPU ms per position: samples (cpu-clock, one per 1/freq s of CPU) / frequency / positions.
ms_per_position() { perf script -i "$1.data" -F ip 2>/dev/null | wc -l | awk -v f="$freq" -v n="$n" '{ printf "%.4f", 1000 * $1 / f / n }'; }
# Summed share (%) of the symbols matching a regular expression.
share() { awk -v re="$2" '{ p = $1; sub(/%/, "", p); $1 = ""; if ($0 ~ re) s += p } END { printf "%.2f", s }' "$1.shares"; }
t1=$(ms_per_position one)
t8=$(ms_per_position eight)
images=$(share eight 'image_arrivals|add_arrival_impulses')
noise=$(share eight 'Rng::fill_uniform')
# FFTW's codelets and planner-free executors (n1fv_12, hc2cfdftv_4, t3fv_32, ...).
fft=$(share one '(^| )(n1b?v?|n2|t1b?u?v?|t2|t3|hc2c[bf]dftv|hc2c[bf]v?|r2c[bf]|r2cb?f?|q1|hf|hb)[a-z]*_[0-9]+ ')
awk -v t1="$t1" -v t8="$t8" -v im="$images" -v no="$noise" -v fft="$fft" 'BEGIN {
  per_mic_images = t8 * im / 100 / 8; per_mic_noise = t8 * no / 100 / 8; one_fft = t1 * fft / 100 / 9
  p = per_mic_images + per_mic_noise + one_fft
  printf "| measure | CPU ms |\n|---|---|\n"
  printf "| 1 mic, per position (T1) | %.3f |\n", t1
  printf "| 8 mics, per position (measured) | %.3f (%.1fx) |\n", t8, t8 / t1
  printf "| per microphone: image arrivals + taps (%.2f%% of the 8-mic run / 8) | %.4f |\n", im, per_mic_images
  printf "| per microphone: white noise (%.2f%% of the 8-mic run / 8) | %.4f |\n", no, per_mic_noise
  printf "| per microphone: one FFT of the length (%.2f%% of the 1-mic run / 9) | %.4f |\n", fft, one_fft
  printf "| per-microphone floor P | %.4f |\n", p
  printf "| 8 mics at least T1 + 7 P | %.3f (**%.2fx**) |\n", t1 + 7 * p, (t1 + 7 * p) / t1
}'
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
