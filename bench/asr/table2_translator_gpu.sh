#!/usr/bin/env bash
# A Table 2 translator (issue 30) trained on a GPU machine, for bench/asr/run_table2.sh to import.
#
# run_table2.sh trains each translator with one command on the CPU (width 16, batch 4, --gan-steps
# steps, seed 0, on the demo's real/GAS training split). The paper's preset (its original decoder,
# two discriminator updates per step) takes the better part of an hour of two cores there, which
# the downstream runs need; this script runs the same command with --device=cuda on a GPU machine:
#
#   here: bench/asr/table2_translator_gpu.sh pack DIR [DEMO_RIRS]
#         the demo's real_train and gas_train lists (DEMO_RIRS, default the demo's data/rirs) and
#         their WAVs into DIR, with paths relative to DIR (the GPU machine has another root);
#   GPU:  bench/asr/table2_translator_gpu.sh train DIR OUT_DIR [NAME] [STEPS]
#         builds ts-rirgan-train against the machine's LibTorch (bench/gan/cuda_check.sh with
#         ONLY_BUILD=1), trains NAME (paper: --config=conf/ts-rirgan-paper.conf; default: no
#         config) for STEPS (default 2000) on CUDA, and writes the model dir as OUT_DIR/NAME.tgz.00,
#         .01, ... (gzip'd tar in 15 MB pieces: a device call returns files of at most 16 MB, and a
#         checkpoint is ~84 MB), OUT_DIR/summary.md (machine, command, time) and the training log;
#   here: cat OUT_DIR/NAME.tgz.* | tar xzf - -C SOMEWHERE
#         (A rehearsal without a GPU: BIN=build/bin DEVICE=cpu ... train DIR OUT_DIR paper 3.)
#   here: bench/asr/run_table2.sh --import-translator NAME=<the untarred model dir> ...
#         checks the model's settings and steps against what run_table2.sh would train, and uses it.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
die() { echo "table2_translator_gpu.sh: ERROR: $*" >&2; exit 1; }

pack() {  # <dir> [demo-rirs]
  local dir=$1 demo=${2:-$root/egs/librispeech_farfield/demo/data/rirs} set line path
  for set in real_train gas_train; do
    [ -s "$demo/$set/rir_list" ] || die "$demo/$set/rir_list missing (run the demo's stages 0-6 first)"
    mkdir -p "$dir/$set"
    : >"$dir/$set.list.tmp"
    while IFS= read -r line; do
      path=${line##* }
      cp "$path" "$dir/$set/"
      echo "${line% *} $set/$(basename "$path")" >>"$dir/$set.list.tmp"
    done <"$demo/$set/rir_list"
    mv "$dir/$set.list.tmp" "$dir/$set.list"
  done
  echo "table2_translator_gpu.sh: packed $(wc -l <"$dir/real_train.list") real and $(wc -l <"$dir/gas_train.list") GAS RIRs into $dir ($(du -sh "$dir" | cut -f1))" >&2
}

train() {  # <dir> <out> [name] [steps]
  local dir out name=${3:-paper} steps=${4:-2000} extra=() t0 build_log
  dir=$(readlink -f "$1"); out=$2
  mkdir -p "$out"; out=$(readlink -f "$out")
  case $name in
    paper) extra=(--config="$root/conf/ts-rirgan-paper.conf") ;;
    default) ;;
    *) die "unknown translator '$name' (paper | default)" ;;
  esac
  t0=$SECONDS
  local work=${TMPDIR:-/tmp}/tsrir_cuda_check bin=${BIN:-}
  if [ -z "$bin" ]; then
    build_log=$out/build
    ONLY_BUILD=1 TARGETS=ts-rirgan-train "$root/bench/gan/cuda_check.sh" "$build_log" || die "build failed: see $build_log"
    export LD_LIBRARY_PATH=$work/deps/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
    bin=$work/build/bin
  fi
  bin=$(readlink -f "$bin")
  local model=$work/models/$name
  # run_table2.sh's command (train_translator) with --device=cuda added.
  local cmd=("$bin/ts-rirgan-train" "${extra[@]}" --width=16 --batch-size=4 --steps="$steps" --seed=0
             --num-threads=2 --overwrite --real=real_train.list --synthetic=gas_train.list --device="${DEVICE:-cuda}" "$model")
  local built=$((SECONDS - t0)) t1=$SECONDS rc=0
  # A run cut by TRAIN_LIMIT_S (default 420 s) writes its checkpoint on SIGTERM: RESUME=1 and the
  # untarred model in $work/models continue it.
  [ "${RESUME:-0}" = 1 ] && cmd+=(--resume)
  (cd "$dir" && timeout -s TERM "${TRAIN_LIMIT_S:-420}" "${cmd[@]}") 2>"$out/train_$name.log" || rc=$?
  {
    echo "# table2_translator_gpu.sh train ($(date -u '+%Y-%m-%d %H:%M UTC'))"
    echo "- machine: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | head -1);" \
         "$(getconf _NPROCESSORS_ONLN) cores of $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); load $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "- build: $built s (bench/gan/cuda_check.sh ONLY_BUILD=1, log in build/)"
    echo "- command (in $dir): ${cmd[*]}"
    echo "- exit $rc after $((SECONDS - t1)) s; steps done: $(tail -1 "$model/loss_log.csv" 2>/dev/null | cut -d, -f1);" \
         "median s/step: $(awk -F, 'NR>2{print $NF}' "$model/loss_log.csv" 2>/dev/null | sort -g | awk '{a[NR]=$1} END{print NR ? a[int((NR+1)/2)] : "n/a"}')"
  } >"$out/summary.md"
  cat "$out/summary.md" >&2
  tar -C "$(dirname "$model")" -cf - "$name" | gzip -1 | split -b 15M -d - "$out/$name.tgz."
  [ $rc = 0 ] || die "training stopped with status $rc: see $out/train_$name.log"
}

case ${1:-} in
  pack) shift; [ $# -ge 1 ] || die "usage: $0 pack DIR [DEMO_RIRS]"; pack "$@" ;;
  train) shift; [ $# -ge 2 ] || die "usage: $0 train DIR OUT_DIR [NAME] [STEPS]"; train "$@" ;;
  *) die "usage: $0 pack DIR [DEMO_RIRS] | train DIR OUT_DIR [NAME] [STEPS]" ;;
esac
