#!/usr/bin/env bash
# Stage 8 without Kaldi (run.sh --asr proxy): the paper's Table 2 protocol on one machine.
# A TTS corpus (make_tts_corpus.sh: train voices / held-out test voices) is reverberated with each
# training RIR set plus real noise (reverberate-data, the stage 7 settings), a compact CTC
# recogniser is trained per set and seed (asr-train), and every model decodes one test set: the
# test voices convolved with the held-out *real* test RIRs plus real noise (asr-decode).
# table2.sh then prints CER/WER per set (mean and spread over seeds) and a paired test of each set
# against GAS over the test utterances.
#
# Usage: run_proxy.sh [options] <rirs-dir> <noise-list> <data-dir> <exp-dir>
#   <rirs-dir> holds <set>_train/rir_list for every set but clean, and real_test/rir_list.
#   --train-sets "clean real gas ..."  --seeds "0"  --snrs 1:2  --num-threads N  --nj N
#   --corpus-opts "..." (make_tts_corpus.sh options)  --train-opts "..." (asr-train options)
#   --baseline gas (the set every other is tested against)  --section FILE (Table 2 markdown)
# Extra training sets (e.g. GAS-ext, from rir-diagnose's extended model) need only
# <rirs-dir>/<name>_train/rir_list and a name in --train-sets.
set -euo pipefail
train_sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq"
seeds="0"
snrs=1:2
num_threads=1
nj=2
corpus_opts=""
# 0.35 M parameters, 25 epochs: what the sensitivity check needed (15 epochs gave 22 %, 25 gave 27 %;
# docs/results/downstream.md); asr-train's defaults (1.6 M parameters) are the
# model to use where CPU allows.
train_opts="--epochs=25 --conv-layers=2 --conv-channels=96 --rnn-layers=2 --rnn-hidden=96 --batch-size=8 --learning-rate=3e-3"
baseline=gas
section=""
while [ $# -gt 4 ] && [[ "$1" == --* ]]; do
  name=${1#--}; name=${name//-/_}
  case $name in
    train_sets|seeds|snrs|num_threads|nj|corpus_opts|train_opts|baseline|section) printf -v "$name" '%s' "$2" ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
[ $# -eq 4 ] || { sed -n '2,18p' "$0" >&2; exit 1; }
rirs=$1 noise_list=$2 data=$3/asr exp=$4/asr
here=$(dirname "$(readlink -f "$0")")
log() { echo "run_proxy.sh: $*" >&2; }
die() { echo "run_proxy.sh: ERROR: $*" >&2; exit 1; }
for p in asr-train asr-decode reverberate-data; do command -v $p >/dev/null || die "$p not on PATH (build the toolkit)"; done
[ -s "$noise_list" ] || die "missing noise list $noise_list (run stage 1)"
[ -s "$rirs/real_test/rir_list" ] || die "missing $rirs/real_test/rir_list (run stage 1)"
for s in $train_sets; do
  [ "$s" = clean ] || [ -s "$rirs/${s}_train/rir_list" ] || die "missing $rirs/${s}_train/rir_list (run stages 2-5)"
done
mkdir -p "$data" "$exp/log"

# shellcheck disable=SC2086
"$here/make_tts_corpus.sh" --nj "$nj" $corpus_opts "$data/tts"

farfield() {  # <in> <rir-list> <out>: reverberated + noise, 16-bit wavs (read once per model)
  local in=$1 list=$2 out=$3 sig
  sig="$snrs $(cat "$in/wav.scp" "$list" "$noise_list" | md5sum)"
  if [ -f "$out/.done" ] && [ "$(cat "$out/.done")" = "$sig" ]; then return; fi
  rm -rf "$out" "$data/wav/$(basename "$out")"
  reverberate-data --rir-set-parameters "1.0, $list" --noise-set-parameters "$noise_list" --snrs "$snrs" \
    --random-seed 0 --num-threads "$num_threads" --write-wavs "$data/wav/$(basename "$out")" "$in" "$out" \
    2>"$exp/log/reverberate_$(basename "$out").log" || { tail "$exp/log/reverberate_$(basename "$out").log" >&2; die "reverberate-data failed for $out"; }
  printf '%s\n' "$sig" >"$out/.done"
}
farfield "$data/tts/test" "$rirs/real_test/rir_list" "$data/test_real"
for s in $train_sets; do
  [ "$s" = clean ] || farfield "$data/tts/train" "$rirs/${s}_train/rir_list" "$data/train_$s"
done

for seed in $seeds; do
  for s in $train_sets; do
    if [ "$s" = clean ]; then tr=$data/tts/train; else tr=$data/train_$s; fi
    m=$exp/${s}_seed$seed
    inputs=("$data/tts/.done"); [ "$s" = clean ] || inputs+=("$tr/.done")
    sig="$train_opts $(cat "${inputs[@]}" | md5sum)"
    if ! { [ -f "$m/.done" ] && [ "$(cat "$m/.done")" = "$sig" ]; }; then
      resume=()
      if [ -f "$m/checkpoint.pt" ] && [ -f "$m/.sig" ] && [ "$(cat "$m/.sig")" = "$sig" ]; then resume=(--resume); else rm -rf "$m"; fi
      mkdir -p "$m"; printf '%s\n' "$sig" >"$m/.sig"
      log "training $s (seed $seed) $( [ ${#resume[@]} -gt 0 ] && echo "(resuming)")"
      start=$SECONDS
      # shellcheck disable=SC2086
      /usr/bin/time -f "%e s %M KB" -o "$m/time.txt" asr-train $train_opts --seed "$seed" --num-threads "$num_threads" \
        --progress-interval 60 ${resume[@]+"${resume[@]}"} "$tr" "$m" 2>"$exp/log/train_${s}_seed$seed.log" ||
        { tail "$exp/log/train_${s}_seed$seed.log" >&2; die "asr-train failed for $s"; }
      asr-decode --num-threads "$num_threads" "$m" "$data/test_real" "$m/decode_test_real" 2>>"$exp/log/train_${s}_seed$seed.log"
      printf '%s\n' "$sig" >"$m/.done"
      log "$s (seed $seed): $(head -n 1 "$m/decode_test_real/cer" | sed 's/%WER/CER/'), $(head -n 1 "$m/decode_test_real/wer") ($((SECONDS - start)) s)"
    fi
  done
done
"$here/table2.sh" --sets "$train_sets" --seeds "$seeds" --baseline "$baseline" "$exp" | tee ${section:+"$section"}
