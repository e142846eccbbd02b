#!/usr/bin/env bash
# TS-RIRGAN speed and memory: training step time and peak RSS at width 16 and 64 (batch 4; the
# program's defaults and the paper's configuration, conf/ts-rirgan-paper.conf), generator forward throughput against the FLOP count (gan_forward_bench), and
# gas-to-real throughput at width 64 (decoders x precisions, batched and unbatched). Inputs: the 170 measured R3VIVAL RIRs
# (48 kHz, resampled to 16 kHz by the programs) as both domains; the content does not change the
# cost. Step times are the median of the logged per-step wall times after the first (warm-up) step.
# The width-16 step is measured at 1 and at [threads] threads; OPENBLAS_NUM_THREADS=1 (the program
# also sets it). PROFILE=1 adds a perf profile (top shared objects and symbols) of the width-16 run.
# Usage: bench/gan/run_bench.sh [build-dir] [threads] [width-64 steps]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build-gan}
threads=${2:-2}
steps64=${3:-3}
bin=$build/bin
for t in ts-rirgan-train gas-to-real gan_forward_bench; do
  [[ -x $bin/$t ]] || { echo "missing $bin/$t (ninja -C $build $t)" >&2; exit 1; }
done
data=$here/../shared/data/rirs/r3vival
[[ -d $data ]] || { echo "needs ../shared/data/rirs/r3vival (real RIRs)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for f in "$data"/*.wav; do b=$(basename "$f" .wav); echo "$b $f"; done > "$work/rir.scp"
n=$(wc -l < "$work/rir.scp")
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $("$here/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), --num-threads=$threads"
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

# median of step_s over steps >= 2 of a loss log
median_step() { awk -F, 'NR>2{print $NF}' "$1" | sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'; }

# A --precision=bfloat16 run that the program refuses on this CPU (its LibTorch sums bfloat16
# products in bfloat16: src/gan/gan_bfloat16.h) becomes a row saying so; any other failure stops.
refused_row() {
  grep -q 'sums bfloat16 convolution products in bfloat16' "$2" || { cat "$2" >&2; exit 1; }
  local cells=""; for ((i = 1; i < $3; ++i)); do cells+=" — |"; done
  echo "| $1 | refused on this CPU (LibTorch sums bfloat16 in bfloat16) |$cells"
}

echo "| run | median wall s/step | CPU s/step (process) | peak RSS MB |"
echo "|---|---|---|---|"
export OPENBLAS_NUM_THREADS=1
# "paper" = --config=conf/ts-rirgan-paper.conf (the original's iteration: 2 x (D_R, D_S) updates,
# then G_SR and G_RS each with its own graph); "defaults" = the program's defaults (residual
# generator, light decoder, one D update, joint G update); --width, --batch-size, --steps,
# --precision and --num-threads are given either way (they come after --config, so they win).
# The translation rows below use the width-64 models trained here.
for spec in "16 12 1 defaults float32" "16 12 $threads defaults float32" "16 12 $threads defaults bfloat16" \
    "16 12 1 paper float32" "16 12 $threads paper float32" "16 12 $threads paper bfloat16" \
    "64 $steps64 $threads paper float32" "64 $steps64 $threads paper bfloat16" "64 $steps64 $threads defaults float32"; do
  set -- $spec
  w=$1; s=$2; t=$3; cfg=$4; prec=$5
  m=$work/m${w}_t${t}_$cfg
  [[ $prec == float32 ]] || m=${m}_$prec
  opts=()
  [[ $cfg == paper ]] && opts+=(--config="$here/conf/ts-rirgan-paper.conf")
  if ! /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$bin/ts-rirgan-train" "${opts[@]}" --real="$work/rir.scp" \
    --synthetic="$work/rir.scp" --width=$w --precision=$prec --batch-size=4 --steps=$s --num-threads=$t \
    --checkpoint-every=100000 --progress-interval=60 "$m" 2> "$work/log"; then
    refused_row "train width $w ($cfg, $prec), batch 4, $t thread(s)" "$work/log" 3; continue
  fi
  read -r wall user sys rss < "$work/time"
  cpu=$(awk -v u="$user" -v s="$sys" -v n="$s" 'BEGIN{printf "%.3f", (u+s)/n}')
  echo "| train width $w ($cfg, $prec), batch 4, $t thread(s), $s steps (CPU/step includes loading $n RIRs) | $(median_step "$m/loss_log.csv") | $cpu | $((rss / 1024)) |"
done
if [[ ${PROFILE:-0} == 1 ]]; then
  perf record -q -o "$work/perf.data" "$bin/ts-rirgan-train" --real="$work/rir.scp" --synthetic="$work/rir.scp" \
    --width=16 --batch-size=4 --steps=12 --num-threads=1 --progress-interval=60 "$work/mprof" 2> /dev/null
  echo; echo "perf, width 16, 1 thread (whole run incl. loading): top shared objects / symbols"
  perf report -q -i "$work/perf.data" --sort dso 2> /dev/null | head -8 || true
  perf report -q -i "$work/perf.data" --sort sym 2> /dev/null | head -15 || true
fi

echo
echo "generator forward, no I/O (bench/gan/gan_forward_bench.cc; median of 3 passes; GFLOP = 2 x multiply-adds of the"
echo "direct form, so with the FFT form of the stride-1 layers (float32 inference) GFLOP/s is an effective rate)"
echo "| width | decoder | batch | threads | precision | M params | GFLOP/RIR | ms/batch | RIRs/s | GFLOP/s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for dec in original light; do
  for prec in float32 bfloat16; do
    for b in 1 16; do
      "$bin/gan_forward_bench" --width=64 --decoder=$dec --batch=$b --threads=$threads --precision=$prec --reps=3
    done
  done
done
# The defaults' generator (residual, 500 Hz correction, light decoder), float32, batch 16, with and
# without each inference change of 2026-11-26 evening, in this run: the FFT form of the stride-1
# layers (--conv=direct: every layer direct, as in training) and the reusing huge-page allocator
# (--allocator=libtorch: LibTorch's own); and of the FFT form's per-bin products shared among the
# threads (2026-11-26 night; --bins=serial: one after another, as torch::matmul runs them).
for variant in "" "--bins=serial" "--conv=direct" "--allocator=libtorch" "--conv=direct --allocator=libtorch"; do
  "$bin/gan_forward_bench" --width=64 --decoder=light --generator=residual --correction-max-hz=500 --batch=16 \
    --threads=$threads --precision=float32 --reps=5 $variant
done
# The opt-in band-gain generator (issue 34): the same model plus its band-gain stage, whose parts
# are timed alone on the last line (band split, knot gains, whole stage).
"$bin/gan_forward_bench" --width=64 --decoder=light --generator=band-gain --correction-max-hz=500 --batch=16 \
  --threads=$threads --precision=float32 --reps=5 --band-gain-profile=1

echo
# Whole process: /usr/bin/time's wall clock of the command, program start and model load included
# (gas-to-real reads the generator file training writes beside the checkpoint).
echo "| translation (width 64, $n RIRs, --batch-size=16 unless said) | RIRs/s (wall, excl. model load) | whole process s (RIRs/s) | CPU s total | peak RSS MB |"
echo "|---|---|---|---|---|"
whole() { awk -v w="$1" -v n="$2" 'BEGIN{printf "%.2f (%.1f)", w, n / w}'; }
for spec in "paper float32 16" "paper float32 1" "paper bfloat16 16" "defaults float32 16" "defaults float32 32" "defaults bfloat16 16"; do
  set -- $spec
  cfg=$1; prec=$2; b=$3
  out=$work/out_${cfg}_${prec}_$b
  if ! /usr/bin/time -f "%e %U %S %M" -o "$work/time_t" "$bin/gas-to-real" --model="$work/m64_t${threads}_$cfg" \
    --batch-size=$b --precision=$prec --num-threads=$threads "$work/rir.scp" "$out" 2> "$work/log_t"; then
    refused_row "gas-to-real, model trained with the $cfg configuration, --precision=$prec --batch-size=$b" "$work/log_t" 4
    continue
  fi
  read -r wall user sys rss < "$work/time_t"
  rate=$(grep -o '[0-9.e+]* RIRs/s' "$work/log_t" | cut -d' ' -f1)
  echo "| gas-to-real, model trained with the $cfg configuration, --precision=$prec --batch-size=$b | $rate | $(whole "$wall" "$n") | $(awk -v u="$user" -v s="$sys" 'BEGIN{printf "%.1f", u+s}') | $((rss / 1024)) |"
done
# The same defaults model over the list three times (3n RIRs, ids made distinct): the one-time cost
# of the first batch (oneDNN kernels, the kept kernel spectra) is then spread over more RIRs.
awk '{print $1 "_" int((NR - 1) / '"$n"'), $2}' "$work/rir.scp" "$work/rir.scp" "$work/rir.scp" > "$work/rir3.scp"
/usr/bin/time -f "%e %U %S %M" -o "$work/time_t" "$bin/gas-to-real" --model="$work/m64_t${threads}_defaults" \
  --batch-size=16 --precision=float32 --num-threads=$threads "$work/rir3.scp" "$work/out_defaults_x3" 2> "$work/log_t"
read -r wall user sys rss < "$work/time_t"
rate=$(grep -o '[0-9.e+]* RIRs/s' "$work/log_t" | cut -d' ' -f1)
echo "| gas-to-real, defaults model, --precision=float32 --batch-size=16, $((3 * n)) RIRs (the list 3 times) | $rate | $(whole "$wall" "$((3 * n))") | $(awk -v u="$user" -v s="$sys" 'BEGIN{printf "%.1f", u+s}') | $((rss / 1024)) |"
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
