#!/usr/bin/env bash
# Stage 8 without Kaldi (run.sh --asr proxy): the paper's Table 2 protocol on one machine.
# A TTS corpus (make_tts_corpus.sh: train voices / held-out test voices) is reverberated with each
# training RIR set plus real noise (reverberate-data with conf/reverberate.conf, stage 7's
# settings), a compact CTC recogniser is trained per set and seed (asr-train), and every model
# decodes the test sets, both made with the held-out *real* test RIRs plus real noise:
#   test_real        the test voices (asr-decode)
#   test_realspeech  real read speech (make_real_speech_dir.sh on --real-speech; skipped, with a
#                    message, when that directory is absent), --real-speech-copies reverberant
#                    copies of each utterance, each with another real test RIR
# table2.py then prints CER/WER per set and test (mean and 95 % interval over the training runs) and
# each set against --baseline with tests over runs (Welch, and a permutation of run labels).
#
# Usage: run_proxy.sh [options] <rirs-dir> <noise-list> <data-dir> <exp-dir>
#   <rirs-dir> holds <set>_train/rir_list for every set but clean, and real_test/rir_list.
#   --train-sets "clean real gas ..."  --seeds "0"  --snrs 1..2  --num-threads N (per model)
#   --jobs N (models trained at once)  --nj N (corpus synthesis jobs)
#   --corpus-opts "..." (make_tts_corpus.sh options)  --corpus-dir DIR (the corpus' place; default
#       <data-dir>/asr/tts: several runs, e.g. two SNR arms, can share one corpus)
#   --train-copies K: K reverberant copies of each training utterance (reverberate-data
#       --num-replications K; each copy its own RIR, noise and SNR draw); asr-train then trains on one
#       copy per utterance per epoch (--sample-copies), drawn from its seed: K times the RIR draws for
#       the cost of one copy per epoch, and each run (seed) its own draws
#   --train-config FILE (asr-train --config; default conf/asr-train-proxy.conf)
#   --train-opts "..." (more asr-train options; they override the config)
#   --real-speech DIR  --real-speech-copies N (4)
#   --baseline gas (the set every other is tested against)  --section FILE (Table 2 markdown)
#   --dose "real ctl_t60x0.5 ctl_t60x0.33|real ctl_drr+6" positive-control chains of growing mismatch
#       (table2.py checks that CER rises along each)
# Outputs: <data-dir>/asr/{tts,test_real,test_realspeech,train_<set>}, models
# <exp-dir>/asr/<set>_seed<k> with decode_<test>/ inside, logs in <exp-dir>/asr/log.
# Every step is skipped when done with the same settings; a model whose settings changed is
# retrained (only the files asr-train and asr-decode wrote are removed).
set -euo pipefail
here=$(dirname "$(readlink -f "$0")")
train_sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext"
seeds="0"
snrs=1..2
num_threads=1
jobs=1
nj=2
corpus_opts=""
corpus_dir=""
train_copies=1
train_config=$(readlink -f "$here/../../../../conf/asr-train-proxy.conf")
train_opts=""
real_speech=""
real_speech_copies=4
baseline=gas
section=""
dose=""
while [ $# -gt 4 ] && [[ "$1" == --* ]]; do
  name=${1#--}; name=${name//-/_}
  case $name in
    train_sets|seeds|snrs|num_threads|jobs|nj|corpus_opts|corpus_dir|train_copies|train_config|train_opts|real_speech|real_speech_copies|baseline|section|dose)
      printf -v "$name" '%s' "$2" ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
[ $# -eq 4 ] || { sed -n '2,33p' "$0" >&2; exit 1; }
rirs=$1 noise_list=$2 data=$3/asr exp=$4/asr
corpus=${corpus_dir:-$data/tts}
[[ "$train_copies" =~ ^[1-9][0-9]*$ ]] || { echo "run_proxy.sh: --train-copies must be >= 1" >&2; exit 1; }
conf_dir=$(readlink -f "$here/../../../../conf")
log() { echo "run_proxy.sh: $*" >&2; }
die() { echo "run_proxy.sh: ERROR: $*" >&2; exit 1; }
for p in asr-train asr-decode reverberate-data; do command -v $p >/dev/null || die "$p not on PATH (build the toolkit)"; done
[ -s "$noise_list" ] || die "missing noise list $noise_list (run stage 1)"
[ -s "$rirs/real_test/rir_list" ] || die "missing $rirs/real_test/rir_list (run stage 1)"
[ -s "$train_config" ] || die "missing asr-train config $train_config"
[ -s "$conf_dir/reverberate.conf" ] || die "missing $conf_dir/reverberate.conf"
for s in $train_sets; do
  [ "$s" = clean ] || [ -s "$rirs/${s}_train/rir_list" ] || die "missing $rirs/${s}_train/rir_list (run stages 2-5)"
done
mkdir -p "$data" "$exp/log" "$exp/markers"
done_with() { [ -f "$1" ] && [ "$(cat "$1")" = "$2" ]; }

# The options as a shell would read them (voice lists are quoted words).
eval "corpus_args=($corpus_opts)"
"$here/make_tts_corpus.sh" --nj "$nj" ${corpus_args[@]+"${corpus_args[@]}"} "$corpus"

farfield() {  # <in> <rir-list> <out> [copies]: reverberated + noise, 16-bit wavs (read once per model)
  local in=$1 list=$2 out=$3 copies=${4:-1} sig name
  name=$(basename "$out")
  sig="$snrs $copies $(cat "$in/wav.scp" "$in/text" "$list" "$noise_list" "$conf_dir/reverberate.conf" "$corpus/.done" | md5sum)"
  done_with "$exp/markers/$name.data" "$sig" && return 0
  reverberate-data --config="$conf_dir/reverberate.conf" --rir-set-parameters "1.0, $list" \
    --noise-set-parameters "$noise_list" --background-snrs "$snrs" --num-replications "$copies" --random-seed 0 \
    --num-threads "$num_threads" --write-wavs "$data/wav/$name" "$in" "$out" 2>"$exp/log/reverberate_$name.log" ||
    { tail "$exp/log/reverberate_$name.log" >&2; die "reverberate-data failed for $out"; }
  printf '%s\n' "$sig" >"$exp/markers/$name.data"
}
tests=(test_real)
farfield "$corpus/test" "$rirs/real_test/rir_list" "$data/test_real"
if [ -z "$real_speech" ]; then
  log "no --real-speech directory: the real-speech test set is skipped"
elif [ ! -d "$real_speech" ]; then
  log "$real_speech is absent: the real-speech test set is skipped"
else
  rc=0; "$here/make_real_speech_dir.sh" "$real_speech" "$data/realspeech" || rc=$?
  if [ $rc -eq 0 ]; then
    farfield "$data/realspeech" "$rirs/real_test/rir_list" "$data/test_realspeech" "$real_speech_copies"
    tests+=(test_realspeech)
  elif [ $rc -eq 2 ]; then
    log "$real_speech holds no transcribed utterances: the real-speech test set is skipped"
  else
    die "make_real_speech_dir.sh failed on $real_speech"
  fi
fi
for s in $train_sets; do
  [ "$s" = clean ] || farfield "$corpus/train" "$rirs/${s}_train/rir_list" "$data/train_$s" "$train_copies"
done

copy_opts=""
[ "$train_copies" -gt 1 ] && copy_opts="--sample-copies=true"
config_sig="$(md5sum <"$train_config") $train_opts $copy_opts"
# Trains (or resumes, or keeps) one model, then decodes every test set it has not decoded yet.
train_and_decode() {  # <set> <seed>
  local s=$1 seed=$2 tr m name sig resume=() start t
  if [ "$s" = clean ]; then tr=$corpus/train; else tr=$data/train_$s; fi
  name=${s}_seed$seed; m=$exp/$name
  # The clean set has no train_<set>.data marker: a failing cat would end the job under set -e.
  sig="$config_sig $(cat "$exp/markers/tts.data" 2>/dev/null || true) $(cat "$exp/markers/train_$s.data" 2>/dev/null || true)"
  if ! done_with "$exp/markers/$name.model" "$sig"; then
    if [ -f "$m/checkpoint.pt" ] && done_with "$exp/markers/$name.sig" "$sig"; then
      resume=(--resume)
    else
      # Another configuration: only what asr-train and asr-decode wrote goes.
      "$here/../remove_tsrir_files.sh" "$m"/decode_* "$m"
      printf '%s\n' "$sig" >"$exp/markers/$name.sig"
    fi
    rm -f "$exp/markers/$name".decode_*
    log "training $s (seed $seed)$( [ ${#resume[@]} -gt 0 ] && echo " (resuming)")"
    start=$SECONDS
    # shellcheck disable=SC2086
    /usr/bin/time -f "%e %U %S %M" -o "$exp/log/time_$name.txt" asr-train --config="$train_config" $train_opts $copy_opts \
      --seed="$seed" --num-threads="$num_threads" --progress-interval=60 ${resume[@]+"${resume[@]}"} "$tr" "$m" \
      2>"$exp/log/train_$name.log" || { tail "$exp/log/train_$name.log" >&2; die "asr-train failed for $s, seed $seed"; }
    printf '%s\n' "$sig" >"$exp/markers/$name.model"
    log "$s (seed $seed) trained in $((SECONDS - start)) s"
  fi
  for t in "${tests[@]}"; do
    local dsig
    dsig="$sig $(cat "$exp/markers/$t.data")"
    done_with "$exp/markers/$name.decode_$t" "$dsig" && continue
    asr-decode --num-threads="$num_threads" "$m" "$data/$t" "$m/decode_$t" 2>>"$exp/log/decode_$name.log" ||
      { tail "$exp/log/decode_$name.log" >&2; die "asr-decode failed for $s, seed $seed, $t"; }
    printf '%s\n' "$dsig" >"$exp/markers/$name.decode_$t"
    log "$s (seed $seed), $t: $(head -n 1 "$m/decode_$t/cer" | sed 's/%WER/CER/'), $(head -n 1 "$m/decode_$t/wer")"
  done
}
# The corpus' own marker, so that a model's signature follows a re-made corpus.
printf '%s\n' "$(cat "$corpus/.done")" >"$exp/markers/tts.data"

# --jobs models at a time; the first failure stops the others (its log's tail is shown).
declare -A running=()
reap() {  # waits for one model; on failure ends the others and stops
  local pid rc=0
  wait -n -p pid "${!running[@]}" || rc=$?
  unset "running[$pid]"
  if [ $rc -ne 0 ]; then
    kill "${!running[@]}" 2>/dev/null || true
    die "stage 8 proxy: a model failed (exit $rc; logs: $exp/log)"
  fi
}
for seed in $seeds; do
  for s in $train_sets; do
    while [ "${#running[@]}" -ge "$jobs" ]; do reap; done
    train_and_decode "$s" "$seed" &
    running[$!]=1
  done
done
while [ "${#running[@]}" -gt 0 ]; do reap; done

titles="TTS test voices"
[[ " ${tests[*]} " == *" test_realspeech "* ]] && titles+="|real speech, ${real_speech_copies} copies"
# Dose-response chains of positive controls (--dose "real ctl_a ctl_b|real ctl_c"; table2.py).
dose_args=()
IFS='|' read -r -a chains <<<"$dose"
for c in ${chains[@]+"${chains[@]}"}; do [ -n "$c" ] && dose_args+=(--dose "$c"); done
python3 "$here/table2.py" --sets "$train_sets" --seeds "$seeds" --baseline "$baseline" --tests "${tests[*]}" \
  --titles "$titles" ${dose_args[@]+"${dose_args[@]}"} "$exp" | tee ${section:+"$section"}
