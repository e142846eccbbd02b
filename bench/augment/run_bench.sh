#!/usr/bin/env bash
# Throughput of reverberate-data on a 1,000-utterance directory (10 s each at 16 kHz, 1 s float
# RIRs, 30 s noises), materialised (--write-wavs) and piped (running every wav.scp pipe through
# bash, as compute-mfcc-feats would), on 1 and 2 threads. Prints a markdown table.
#
# Usage: bench/augment/run_bench.sh [<bin-dir>] [<num-utterances>]
#   bin-dir defaults to build-augment/bin; the test data lives in a temp dir removed at exit.
# Signals are synthetic (stated in RESULTS.md): "speech" = pink noise amplitude-modulated at
# 4 Hz (syllable rate) by sox; RIRs = exponentially decaying white noise with a direct-path
# impulse, written as 32-bit float like TS-RIR's outputs; noises = brown noise.
set -euo pipefail
bench_root=$(cd "$(dirname "$0")/../.." && pwd)
BIN=$(cd "${1:-$(dirname "$0")/../../build-augment/bin}" && pwd)
N=${2:-1000}
NUM_RIRS=20
NUM_NOISES=5
WORK=$(mktemp -d /tmp/tsrir_bench_augment.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
mkdir -p audio rirs noise data/in

echo "generating $N x 10 s utterances, $NUM_RIRS RIRs, $NUM_NOISES noises in $WORK ..." >&2
gen_utts() {  # $1 = first index, $2 = step (two generators in parallel)
  for ((i = $1; i < N; i += $2)); do
    sox -q -n -r 16000 -b 16 -c 1 "audio/u$(printf %05d "$i").wav" synth 10 pinknoise tremolo 4 90 gain -8
  done
}
gen_utts 0 2 & gen_utts 1 2 & wait
for ((i = 0; i < N; i++)); do
  id=$(printf %05d "$i"); spk=spk$(( i % 50 ))
  echo "$spk-u$id $WORK/audio/u$id.wav" >> data/in/wav.scp.unsorted
  echo "$spk-u$id $spk" >> data/in/utt2spk.unsorted
done
LC_ALL=C sort data/in/wav.scp.unsorted > data/in/wav.scp && rm data/in/wav.scp.unsorted
LC_ALL=C sort data/in/utt2spk.unsorted > data/in/utt2spk && rm data/in/utt2spk.unsorted
for ((r = 0; r < NUM_RIRS; r++)); do
  # 1 s decaying noise tail (T60 ~0.5 s) preceded by a direct-path impulse at 5 ms.
  sox -q -n -r 16000 -e floating-point -b 32 -c 1 rirs/tail$r.wav synth 1 whitenoise vol 0.2 fade l 0 1 0.9
  sox -q -n -r 16000 -e floating-point -b 32 -c 1 rirs/direct$r.wav synth 0.00006 square vol 0.9 pad 0.005 0.99494
  sox -q -m rirs/direct$r.wav rirs/tail$r.wav -e floating-point -b 32 rirs/rir$r.wav trim 0 1
  echo "--rir-id rir$r --room-id room$(( r % 4 )) $WORK/rirs/rir$r.wav" >> rir_list
done
for ((k = 0; k < NUM_NOISES; k++)); do
  sox -q -n -r 16000 -b 16 -c 1 noise/n$k.wav synth 30 brownnoise vol 0.5
  echo "--noise-id n$k --noise-type point-source $WORK/noise/n$k.wav" >> noise_list
done

OPTS=(--rir-set-parameters "1.0, $WORK/rir_list" --noise-set-parameters "$WORK/noise_list" --snrs 1:2 --random-seed 1)
AUDIO_S=$((N * 10))
# Wall clock, and CPU time (user + sys of the process and all its children): on a shared,
# loaded machine the CPU column is the stable one.
timed() {  # timed <result-file> <command...>
  local out=$1; shift
  /usr/bin/time -f "%e %U %S" -o "$out" "$@"
}
row() {  # mode threads time-file
  read -r wall user sys < "$3"
  awk -v m="$1" -v t="$2" -v s="$wall" -v c="$(echo "$user + $sys" | bc -l)" -v n="$N" -v a="$AUDIO_S" \
    'BEGIN { printf "| %-12s | %7d | %8.2f | %9.1f | %8.2f | %10.0f | %11.2f | %13.0f |\n", m, t, s, n / s, 1000 * s / n, a / s, 1000 * c / n, n / c }'
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
echo "| mode         | threads | wall (s) | utt / s   | ms / utt | x realtime | CPU ms/utt | utt / CPU-s |"
echo "|--------------|---------|----------|-----------|----------|------------|-------------|---------------|"
for threads in 1 2; do
  sync
  timed t_wav$threads "$BIN/reverberate-data" "${OPTS[@]}" --write-wavs "$WORK/wavs$threads" --num-threads "$threads" data/in data/out_wav$threads 2> log_wav$threads
  row materialised "$threads" t_wav$threads
done
cmp <(cd wavs1 && cat $(ls | head -20)) <(cd wavs2 && cat $(ls | head -20)) > /dev/null || { echo "1- and 2-thread outputs differ" >&2; exit 1; }

timed t_pipe_dir "$BIN/reverberate-data" "${OPTS[@]}" data/in data/out_pipe 2> log_pipe
echo "pipe mode: writing the data dir took $(cut -d' ' -f1 t_pipe_dir) s" >&2
# Each pipe run as compute-mfcc-feats would: bash -c "<pipe without the final |>".
cat > run_pipes.sh <<'EOS'
run_part() {
  while read -r id pipe; do
    bash -c "${pipe%|}" > /dev/null 2>> log_pipes || { echo "pipe failed: $id" >&2; exit 1; }
  done < "$1"
}
for p in "$@"; do run_part "$p" & done
wait
EOS
for threads in 1 2; do
  split -n "l/$threads" -d data/out_pipe/wav.scp part$threads.
  timed t_pipe$threads bash run_pipes.sh part$threads.*
  row piped "$threads" t_pipe$threads
done
# One piped utterance must equal the materialised one (same seed, same draws).
first=$(head -1 data/out_pipe/wav.scp | cut -d' ' -f1)
bash -c "$(head -1 data/out_pipe/wav.scp | cut -d' ' -f2- | sed 's/|$//')" 2>/dev/null | cmp - "wavs1/$first.wav" \
  && echo "piped == materialised for $first" >&2
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
echo "machine: $("$bench_root/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); $(date -u +%Y-%m-%d)" >&2
