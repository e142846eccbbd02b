#!/usr/bin/env bash
# Table 2 of the downstream experiment with its positive controls (issue 30), resumable in pieces.
#
# What it runs (each step is skipped when done with the same inputs, so the table can be made in
# pieces of a few sets, seeds or one arm at a time; every piece appends its command, start, end and
# load to <out>/pieces.md):
#   1. the demo's stages 0-6 (run.sh --demo --stop-stage 6: real R3VIVAL RIRs split by source
#      position, GAS, GAS+EQ, the demo's small translator's G sets, GAS-ext);
#   2. positive controls: the real training RIRs with a known mismatch (rir-perturb): T60 x0.5,
#      x0.33, x2, DRR -6 / +6 dB, low-frequency ringing +10 dB;
#   3. two trained translators on the demo's real/GAS training split: the program's defaults and the
#      paper's preset (conf/ts-rirgan-paper.conf), both width 16, batch 4, --gan-steps steps; their
#      G(GAS), G(GAS+EQ), G(GAS)+EQ training sets (gas-to-real, rir-eq apply with the demo's EQ);
#   4. per SNR arm (paper: 1..2 dB, the paper's; reverb: 15..25 dB, reverberation-dominated): the
#      proxy recogniser (local/asr/run_proxy.sh, conf/asr-train-proxy.conf) trained per set and seed
#      on one shared TTS corpus (24 voices x 50 utterances; 6 held-out voices x 40 for the test) with
#      --train-copies reverberant copies per utterance, decoded on TTS and real speech convolved with
#      the held-out real test RIRs plus real noise at the arm's SNR; Table 2 per arm (table2.py:
#      run-level means with 95 % intervals, each set against GAS over runs, the controls' dose chains).
#
# Usage: bench/asr/run_table2.sh [--arms "paper reverb"] [--seeds "0 1 2 3 4"] [--sets "..."]
#          [--jobs 2] [--out DIR] [--gan-steps 2000] [--train-copies 3] [--import-translator NAME=DIR]
#          [--corpus-seed 0]
# --import-translator paper=DIR (or default=DIR) uses a model trained elsewhere with this script's
# command, e.g. on a GPU by bench/asr/table2_translator_gpu.sh, after checking that its settings and
# step count are the ones this script would train (bench/asr/translator_matches.py).
# --corpus-seed N (N > 0) draws another TTS corpus (make_tts_corpus.sh --seed N: other sentences,
# rates and pitches for the same voices, train and test) into <out>/corpus_seedN, and trains and
# tests each arm on it in <out>/<arm>_corpusN: the same RIR sets and translators, a second corpus draw.
# e.g. the instrument check alone: bench/asr/run_table2.sh --arms reverb --sets "real ctl_t60x0.5 ctl_t60x0.33"
# Default out: egs/librispeech_farfield/demo/table2. A piece stopped by Ctrl-C resumes where it
# stopped (a model in training resumes from its last epoch).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
recipe=$root/egs/librispeech_farfield
controls="ctl_t60x0.5 ctl_t60x0.33 ctl_t60x2 ctl_drr-6 ctl_drr+6 ctl_lf+10"
sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext gas_gsrp gas_eq_gsrp gas_gsrp_eq gas_gsrt $controls"
arms="paper reverb"
seeds="0 1 2 3 4"
jobs=2
out=$recipe/demo/table2
gan_steps=2000
train_copies=3
corpus_seed=0
imports=()
cmdline="$0 $*"
while [ $# -gt 0 ]; do
  case $1 in
    --sets) sets=$2 ;; --arms) arms=$2 ;; --seeds) seeds=$2 ;; --jobs) jobs=$2 ;; --out) out=$2 ;;
    --gan-steps) gan_steps=$2 ;; --train-copies) train_copies=$2 ;; --import-translator) imports+=("$2") ;;
    --corpus-seed) corpus_seed=$2 ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
mkdir -p "$out"; out=$(readlink -f "$out")
cd "$recipe"
. ./path.sh
log() { echo "run_table2.sh: $*" >&2; }
die() { echo "run_table2.sh: ERROR: $*" >&2; exit 1; }
for p in rir-perturb ts-rirgan-train gas-to-real rir-eq asr-train asr-decode reverberate-data; do
  command -v $p >/dev/null || die "$p not on PATH (build the toolkit)"
done
snrs_of() { case $1 in paper) echo 1..2 ;; reverb) echo 15..25 ;; *) die "unknown arm '$1' (paper | reverb)" ;; esac; }
for a in $arms; do snrs_of "$a" >/dev/null; done
[[ "$corpus_seed" =~ ^[0-9]+$ ]] || die "--corpus-seed must be a number >= 0, got '$corpus_seed'"
demo_rirs=$recipe/demo/data/rirs
rirs=$out/rirs
machine="$(getconf _NPROCESSORS_ONLN) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
start_time=$(date -u '+%Y-%m-%d %H:%M UTC'); start_load=$(cut -d' ' -f1-3 /proc/loadavg); t0=$SECONDS
( while sleep 60; do cut -d' ' -f1 /proc/loadavg; done ) >"$out/load.$$.txt" &
sampler=$!
trap 'kill $sampler 2>/dev/null || true' EXIT

done_with() { [ -f "$1" ] && [ "$(cat "$1")" = "$2" ]; }
mark() { printf '%s\n' "$2" >"$1.tmp" && mv "$1.tmp" "$1"; }

# ---- 1. the demo's RIR sets ----
prepare_demo() {
  [ -s "$demo_rirs/real_test/rir_list" ] && [ -s "$demo_rirs/gas_ext_train/rir_list" ] && [ -f "$demo_rirs/split/split.txt" ] &&
    grep -q groups= "$demo_rirs/split/split.txt" && return 0
  log "running the demo's stages 0-6 (real RIRs split by source position, GAS, EQ, G, GAS-ext)"
  ./run.sh --demo --stop-stage 6 >"$out/demo_stages.log" 2>&1 || { tail "$out/demo_stages.log" >&2; die "run.sh --demo --stop-stage 6 failed"; }
}

# ---- 2. positive controls ----
control_opts() {
  case $1 in
    ctl_t60x*) echo "--t60-scale=${1#ctl_t60x}" ;;
    ctl_drr*) echo "--drr-offset-db=${1#ctl_drr}" ;;
    ctl_lf*) echo "--lf-ringing-db=${1#ctl_lf}" ;;
    *) die "unknown control $1" ;;
  esac
}
make_control() {  # <set>
  local s=$1 o sig
  o=$(control_opts "$s")
  sig="$o $(md5sum <"$demo_rirs/real_train/rir_list")"
  done_with "$rirs/${s}_train/.done" "$sig" && return 0
  rir-perturb $o --seed=0 --num-threads=2 --overwrite "$demo_rirs/real_train/rir_list" "$rirs/${s}_train" 2>"$out/log/$s.log" ||
    { tail "$out/log/$s.log" >&2; die "rir-perturb $o failed"; }
  rir-metrics --reference="$demo_rirs/real_train/rir_list" "$rirs/${s}_train/rir_list" >"$rirs/${s}_train/metrics.txt" 2>>"$out/log/$s.log"
  mark "$rirs/${s}_train/.done" "$sig"
  log "control $s: $(tail -n 1 "$out/log/$s.log" | sed 's/^rir-perturb: perturbed //')"
}

# ---- 3. trained translators and their G sets ----
translator_options() {  # <name>: the options beside width, batch and steps
  case $1 in
    default) echo "" ;;
    paper) echo "--config=$root/conf/ts-rirgan-paper.conf" ;;
    *) die "unknown translator '$1' (default | paper)" ;;
  esac
}
translator_sig() {  # <name>: what the model is made from; a change trains it anew
  # The settings a model trained now would store (--print-settings: every option's value, new
  # defaults included), not --help's text, so that a reworded help does not retrain it.
  local settings
  # shellcheck disable=SC2046
  settings=$(ts-rirgan-train $(translator_options "$1") --width=16 --batch-size=4 --seed=0 \
    --real="$demo_rirs/real_train/rir_list" --synthetic="$demo_rirs/gas_train/rir_list" --print-settings "$out/gan/$1" | md5sum) ||
    die "ts-rirgan-train --print-settings failed"
  echo "steps=$gan_steps settings=$settings $(md5sum <"$demo_rirs/real_train/rir_list") $(md5sum <"$demo_rirs/gas_train/rir_list")"
}
train_translator() {  # <name>
  local name=$1 dir=$out/gan/$1 sig extra
  extra=$(translator_options "$name"); sig=$(translator_sig "$name")
  done_with "$dir.done" "$sig" && return 0
  local resume=()
  [ -f "$dir/checkpoint.pt" ] && done_with "$dir.sig" "$sig" && resume=(--resume)
  mkdir -p "$out/gan"; mark "$dir.sig" "$sig"
  log "training the $name translator ($extra --width=16 --batch-size=4 --steps=$gan_steps)"
  # shellcheck disable=SC2086
  ts-rirgan-train $extra --width=16 --batch-size=4 --steps="$gan_steps" --seed=0 --num-threads=2 --overwrite \
    --real="$demo_rirs/real_train/rir_list" --synthetic="$demo_rirs/gas_train/rir_list" ${resume[@]+"${resume[@]}"} "$dir" \
    2>"$out/log/gan_$name.log" || { tail "$out/log/gan_$name.log" >&2; die "ts-rirgan-train ($name) failed"; }
  mark "$dir.done" "$sig"
}
import_translator() {  # <name>=<model dir>: a model trained with train_translator's command elsewhere
  local name=${1%%=*} from=${1#*=} dir sig extra
  dir=$out/gan/$name; extra=$(translator_options "$name"); sig=$(translator_sig "$name")
  [ -f "$from/settings.txt" ] && [ -f "$from/checkpoint.pt" ] && [ -f "$from/loss_log.csv" ] ||
    die "--import-translator $1: $from has no settings.txt, checkpoint.pt and loss_log.csv"
  # shellcheck disable=SC2086
  python3 "$root/bench/asr/translator_matches.py" "$from" --program="$(command -v ts-rirgan-train)" --steps="$gan_steps" $extra --width=16 --batch-size=4 --seed=0 ||
    die "--import-translator $1: not the model this script trains (above)"
  mkdir -p "$out/gan"; rm -rf "$dir.tmp"; cp -r "$from" "$dir.tmp"; rm -rf "$dir"; mv "$dir.tmp" "$dir"
  mark "$dir.sig" "$sig"; mark "$dir.done" "$sig"
  log "imported the $name translator from $from"
  echo "- imported the $name translator from \`$from\`: $(grep -h 'command\|machine\|exit' "$from/trained_on.md" 2>/dev/null | tr '\n' ' ')" >>"$out/pieces.md"
}
# A set made anew: the far-field data and models made from its old content go (run_proxy.sh's
# markers follow the list's paths, which stay the same), so that every arm trains on the new one.
forget_set() {  # <set>
  local m
  for m in "$out"/*/exp/asr/markers/train_"$1".data; do [ -e "$m" ] && rm -f "$m"; done
  return 0
}
make_g_set() {  # <set> <sig> <command...>
  local set=$1 sig=$2
  shift 2
  done_with "$rirs/${set}_train/.done" "$sig" && return 0
  "$@" 2>>"$out/log/$set.log" || { tail "$out/log/$set.log" >&2; die "making $set failed"; }
  forget_set "$set"
  mark "$rirs/${set}_train/.done" "$sig"
}
make_g_sets() {  # <suffix> <model-dir>: gas_gsr<suffix>, gas_eq_gsr<suffix>, gas_gsr<suffix>_eq
  local x=$1 model=$2 sig
  sig="$(cat "$model.done" 2>/dev/null || echo demo) $(md5sum <"$demo_rirs/gas_train/rir_list")"
  make_g_set "gas_gsr$x" "$sig" gas-to-real --model="$model" --format=int16 --num-threads=2 --overwrite \
    "$demo_rirs/gas_train/rir_list" "$rirs/gas_gsr${x}_train"
  make_g_set "gas_eq_gsr$x" "$sig" gas-to-real --model="$model" --format=int16 --num-threads=2 --overwrite \
    "$demo_rirs/gas_eq_train/rir_list" "$rirs/gas_eq_gsr${x}_train"
  make_g_set "gas_gsr${x}_eq" "$sig" rir-eq apply --config="$root/conf/rir-eq-apply.conf" --seed=0 --num-threads=2 --overwrite \
    "$recipe/demo/exp/eq/eq.model" "$rirs/gas_gsr${x}_train/rir_list" "$rirs/gas_gsr${x}_eq_train"
}

prepare_rirs() {
  mkdir -p "$rirs" "$out/log"
  prepare_demo
  local i
  for i in ${imports[@]+"${imports[@]}"}; do import_translator "$i"; done
  # The demo's sets, linked; the demo's small translator (width 8, 300 steps) is kept as a labelled
  # row. When the demo made one anew (its .done changed), what was trained on the old one goes.
  local pair s from
  for pair in real:real gas:gas gas_eq:gas_eq gas_ext:gas_ext gas_gsrt:gas_gsr real_test:real_test; do
    s=${pair%%:*}; from=$demo_rirs/${pair#*:}
    if [ "$s" = real_test ]; then ln -sfn "$from" "$rirs/real_test"; else from+=_train; ln -sfn "$from" "$rirs/${s}_train"; fi
    done_with "$rirs/$s.source" "$(cat "$from/.done")" && continue
    if [ -f "$rirs/$s.source" ]; then
      # Other test RIRs: every far-field set and model of every arm is made anew.
      if [ "$s" = real_test ]; then rm -f "$out"/*/exp/asr/markers/*; else forget_set "$s"; fi
    fi
    mark "$rirs/$s.source" "$(cat "$from/.done")"
  done
  for s in $sets; do case $s in ctl_*) make_control "$s" ;; esac; done
  if [[ " $sets " == *" gas_gsr "* || " $sets " == *" gas_eq_gsr "* || " $sets " == *" gas_gsr_eq "* ]]; then
    train_translator default
    make_g_sets "" "$out/gan/default"
  fi
  if [[ " $sets " == *" gas_gsrp"* || " $sets " == *" gas_eq_gsrp "* ]]; then
    train_translator paper
    make_g_sets p "$out/gan/paper"
  fi
}

# The corpus: make_tts_corpus.sh's defaults (24 training voices x 50 utterances, 6 held-out voices x 40),
# drawn with --corpus-seed (0: the table's own corpus and arm dirs, as before the option).
corpus_opts=""; corpus_dir=$out/corpus; arm_suffix=""
if [ "$corpus_seed" != 0 ]; then
  corpus_opts="--seed $corpus_seed"; corpus_dir=$out/corpus_seed$corpus_seed; arm_suffix=_corpus$corpus_seed
fi

run_arm() {  # <arm>
  local arm=$1 d=$out/$1$arm_suffix
  mkdir -p "$d"
  local dose="real ctl_t60x0.5 ctl_t60x0.33|real ctl_t60x2|real ctl_drr-6|real ctl_drr+6|real ctl_lf+10" chains="" c
  # Only chains whose sets are all in this piece.
  IFS='|' read -r -a all <<<"$dose"
  for c in "${all[@]}"; do
    local ok=true s
    for s in $c; do [[ " $sets " == *" $s "* ]] || ok=false; done
    $ok && chains+="${chains:+|}$c"
  done
  log "arm $arm (SNR $(snrs_of "$arm") dB): sets $sets; seeds $seeds"
  local_args=(--train-sets "$sets" --seeds "$seeds" --jobs "$jobs" --snrs "$(snrs_of "$arm")"
              --corpus-dir "$corpus_dir" --corpus-opts "$corpus_opts" --train-copies "$train_copies"
              --real-speech "$root/../shared/data/speech" --dose "$chains" --section "$d/table2.md")
  local/asr/run_proxy.sh "${local_args[@]}" "$rirs" demo/data/noise/noise_list "$d/data" "$d/exp"
}

prepare_rirs
for a in $arms; do run_arm "$a"; done

kill $sampler 2>/dev/null || true
wall=$((SECONDS - t0))
{
  echo "- \`$cmdline\`: $start_time -> $(date -u '+%H:%M UTC'), ${wall} s wall; $machine; load at start $start_load," \
       "during the piece $(awk '{ s += $1; n++; if ($1 > m) m = $1 } END { if (n) printf "mean %.1f, max %.1f", s / n, m; else print "n/a" }' "$out/load.$$.txt")"
} >>"$out/pieces.md"
rm -f "$out/load.$$.txt"
log "piece done in $wall s (recorded in $out/pieces.md)"
