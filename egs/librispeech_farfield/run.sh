#!/usr/bin/env bash
# The TS-RIR paper's experiment (Ratnarajah et al., ASRU 2021, sec. 4) as a Kaldi-style recipe:
# real RIRs -> synthetic RIRs (GAS) -> sub-band EQ and TS-RIRGAN translation -> Table 1 (acoustic
# parameters) -> far-field LibriSpeech data dirs -> Kaldi chain TDNN training and decoding (Table 2).
#
#   ./run.sh [options]              the full experiment (downloads LibriSpeech and BUT ReverbDB)
#   ./run.sh --demo                 stages 0-7 on embedded data, < 10 minutes on 2 cores
#   ./run.sh --demo --demo-size tiny   the reduced demo the test suite runs (~2 minutes)
#
# Stages (--stage N --stop-stage M; each skips work that is complete for the same settings, and
# fails loudly, naming the file, when an input is missing):
#   0  get data: LibriSpeech (openslr 12) and BUT ReverbDB, skipped when present
#      (--demo: make the embedded corpus, local/make_demo_data.sh)
#   1  Kaldi data dirs for the speech; real RIR and noise lists; the seeded 773/194/242
#      train/dev/test RIR split (staircase and repeated RIRs dropped)
#   2  GAS: one synthetic RIR per real RIR from its room/source/microphone metadata with random
#      absorption (rir-room-list, rir-simulate via $train_cmd JOB=1:$nj)
#   3  sub-band EQ fitted on the real training RIRs (rir-eq fit)
#   4  TS-RIRGAN trained on real vs GAS training RIRs (ts-rirgan-train), or --gan-model given
#   5  the RIR sets GAS, GAS+EQ, G(GAS), G(GAS+EQ), G(GAS)+EQ for the train and test splits, and
#      GAS-ext: rir-diagnose fits its extended model on the real training RIRs, rir-simulate renders it
#   6  Table 1: rir-metrics --reference=<real test RIRs> over the test-split sets -> RESULTS.md
#   7  far-field data dirs (reverberate-data): one training set per RIR set, dev and test sets
#      with real RIRs; real noise at a random offset, looped, SNR 1-2 dB; validated
#   8  Table 2, one recogniser per training set, decoded on real-RIR far-field test speech:
#      --asr kaldi (default when KALDI_ROOT is set, except for --demo): chain TDNN training and decoding through
#      Kaldi's scripts (local/kaldi/run_asr.sh), WERs in the paper's Table 2 layout -> RESULTS.md;
#      --asr proxy (default without Kaldi): local/asr/run_proxy.sh, a TTS corpus (train/test voices)
#      reverberated with each training set + real noise, a compact CTC recogniser per set and seed
#      (asr-train/asr-decode), tested on test voices ⊛ held-out real test RIRs + real noise; CER,
#      WER and a paired test against GAS -> RESULTS.md (the demo runs it: Table 1 and Table 2).
# Set names read left to right as the operations applied: gas_eq = GAS+EQ, gas_gsr = G(GAS),
# gas_eq_gsr = G(GAS+EQ), gas_gsr_eq = G(GAS)+EQ (the paper's best), real, clean (no RIR).
set -euo pipefail
# Whatever `set -e` stops on says so: the command, its line and its exit status (a stage's own
# checks die with a sentence first; this catches what they do not foresee).
trap 'rc=$?; echo "run.sh: ERROR: line $LINENO: command failed (exit status $rc): $BASH_COMMAND" >&2' ERR
cd "$(dirname "$(readlink -f "$0")")"

# ---- configuration (every variable is an option: --name value, dashes for underscores) ----
stage=0
stop_stage=8
demo=false            # run on embedded data (README's first command)
demo_size=small       # small (README) | tiny (the test suite)
nj=8                  # parallel jobs ($train_cmd JOB=1:$nj)
num_threads=4         # threads per program
seed=0                # every random choice: split, absorption, EQ draws, GAN, mixing
corpus_dir=corpora    # downloads
librispeech_url=https://www.openslr.org/resources/12
librispeech_parts="train-clean-100 train-clean-360 dev-clean test-clean"
librispeech_dir=""    # default $corpus_dir/LibriSpeech; an existing copy is used as is
but_url=http://merlin.fit.vutbr.cz/ReverbDB/BUT_ReverbDB_rel_19_06_RIR-Only.tgz
but_dir=""            # default $corpus_dir/BUT_ReverbDB; an existing copy is used as is
but_skip_rooms=VUT_FIT_L227   # the staircase
shared_data=../../../shared/data   # demo: real audio read in place when present
data=data
exp=exp
results=RESULTS.md
split_sizes=773:194:242
# RIRs that share these metadata fields (room size and source position) go to one split: no source
# position is in both training and test, in any room condition (local/split_rirs.sh). "" = single RIRs.
split_group_fields="3 4 5 6 7 8"
absorption_range=0.1,0.6   # rir-room-list: uniform random absorption per RIR ...
absorption_draw=surface    # ... drawn per surface (rir | surface | surface-band)
sim_model=gas
standin_model=gas     # demo without ../shared/data/rirs: model of the stand-in "real" RIRs
eq_opts="--model=indep"
gan_model=""          # a trained TS-RIRGAN (model dir or checkpoint.pt): skips stage 4's training
gan_steps=20000
gan_width=64
gan_batch_size=64
gan_device=cpu
gan_opts=""           # extra ts-rirgan-train options (default: the program's defaults, which pass the
                      # translation-fidelity suite (bench/RESULTS.md); the paper's exact training: "--config=../../conf/ts-rirgan-paper.conf",
                      # the defaults before 2026-12-04: "--config=../../conf/ts-rirgan-residual.conf")
gan_num_threads=""    # default: --num-threads. Until 2026-12-07 the demo used 1: when 2 LibTorch threads
                      # split each operator they spin-waited on a busy 2-core machine (~10x slower than 1).
                      # Since 2026-12-05 ts-rirgan-train runs its step's two halves on one thread each,
                      # the same model as 1 thread (tests/gan GanCli.TwoThreadsTrainAsOne); beside two
                      # other trainings, width 8, batch 4: 0.43-0.46 s/step at 2 threads, 0.58-0.68 at 1
                      # (bench/gan/demo_threads.sh; bench/RESULTS.md, "The demo's GAN training on 2 threads")
metrics_definition=irstats
snrs=1..2             # SNR range lo..hi dB (reverberate-data --background-snrs; Kaldi lists a:b:c work too)
write_wavs=false      # far-field dirs: pipes in wav.scp (Kaldi's way) or 16-bit wavs
rir_sets="gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext"
train_sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext"   # stages 7-8
kaldi_stage=0         # local/kaldi/run_asr.sh --stage
kaldi_opts=""         # more local/kaldi/run_asr.sh options, e.g. "--stop-after gmm --lm-text <file>"
asr=""                # stage 8: kaldi | proxy (default: proxy for --demo, never downloading; else kaldi
                      # when KALDI_ROOT is set, and for the full experiment a skip with a message)
asr_seeds="0"         # proxy: one model per training set and seed
asr_num_threads=1     # proxy: LibTorch threads per model (1: threads spin-wait on a busy machine)
asr_jobs=2            # proxy: models trained at once
asr_corpus_opts=""    # proxy: local/asr/make_tts_corpus.sh options (default: its own)
asr_train_config=../../conf/asr-train-proxy.conf   # proxy: asr-train --config (Table 2's configuration)
asr_train_opts=""     # proxy: more asr-train options, overriding the config
asr_train_sets=""     # proxy: its training sets (default: $train_sets); ctl_* names are positive
                      # controls that stage 5 makes from the real training RIRs with rir-perturb:
                      # ctl_t60x<S> (T60 x S), ctl_drr<+-D> (direct sound +-D dB), ctl_lf<+L> (LF ringing)
asr_train_copies=3    # proxy: reverberant copies per training utterance, one per epoch (run_proxy.sh)
asr_dose=""           # proxy: dose-response chains checked in Table 2, e.g. "real ctl_t60x0.33"
lm_url=www.openslr.org/resources/11

help_message="Usage: $0 [options]   (see the top of $0 for the stages)
  --demo true|false, --demo-size small|tiny, --stage N, --stop-stage M, --nj N, --num-threads N,
  --data DIR, --exp DIR, --results FILE, --corpus-dir DIR, --librispeech-dir DIR, --but-dir DIR,
  --gan-model DIR, --gan-steps N, --gan-width W, --seed N, --snrs lo..hi, ... (every variable above)
e.g.: $0 --demo
      $0 --stage 2 --stop-stage 6 --nj 32 --gan-model exp/tsrirgan
Environment:
  KALDI_ROOT  a compiled Kaldi checkout: enables stage 8's Kaldi training and decoding (the default
              of the full experiment; the demo uses the proxy unless --asr kaldi, then with an offline
              LM), Kaldi's run.pl/queue.pl/slurm.pl and validate_data_dir.sh
  TSRIR_CMD   how parallel jobs run (cmd.sh): run.pl (default with Kaldi), queue.pl (SGE; reads
              conf/queue.conf), slurm.pl (reads conf/slurm.conf); without Kaldi local/run_jobs.sh.
              A program run with --num-threads N asks the queue for N slots (--num-threads N to \$cmd);
              conf/queue.conf and conf/slurm.conf are copied into every directory jobs start from
  TSRIR_BIN   tsrir's bin/ (default ../../build/bin); compute nodes need the same absolute path
See docs/recipe.md for cluster set-up, GPU, disk and time per stage."

# `--demo` alone (the README's form) means --demo true; --demo also changes defaults, which
# options given on the command line still override.
args=()
while [ $# -gt 0 ]; do
  if [ "$1" = --demo ] && { [ $# -eq 1 ] || [ "${2#--}" != "$2" ]; }; then args+=(--demo true); shift
  else args+=("$1"); shift; fi
done
set -- ${args[@]+"${args[@]}"}
for ((i = 1; i < $#; i++)); do
  j=$((i + 1))
  if [ "${!i}" = --demo ]; then demo=${!j}; fi
  if [ "${!i}" = --demo-size ]; then demo_size=${!j}; fi
done
if [ "$demo" = true ]; then
  data=demo/data; exp=demo/exp; results=demo/RESULTS.md
  nj=2; num_threads=2; write_wavs=true
  # The program's defaults (the configuration that passes tests/gan's translation-fidelity suite,
  # issue 34); ts-rirgan-train stops with an error if its generator collapses.
  gan_opts=""
  case $demo_size in
    # Steps and width bound the demo's GAN training on 2 cores. The small demo trains the defaults
    # briefly (width 8, batch 4, 300 steps, a few minutes), short of what the fidelity suite
    # measures (width 16, 2000 steps: ~25 minutes; bench/asr/run_table2.sh's G rows) and far from
    # the paper's model (RESULTS.md says so); the tiny demo only proves that the pipeline runs.
    tiny) gan_steps=6; gan_width=4; gan_batch_size=4 ;;
    small) gan_steps=300; gan_width=8; gan_batch_size=4 ;;
  esac
  # Stage 8 runs the proxy recogniser (no Kaldi needed). The small demo: Table 2's configuration
  # (conf/asr-train-proxy.conf, make_tts_corpus.sh's defaults; docs/results/downstream.md).
  # The tiny demo only proves that stage 8 runs: 2 utterances per voice, one epoch of a toy model.
  # Six models, so that stage 8 stays within its time before issue 30 (545 s on the idle 2-core
  # VM; eight models of Table 2's configuration took 663 s): clean, real, GAS, the paper's best
  # post-processing G(GAS)+EQ, GAS-ext and the positive control T60 x0.33 (the size of GAS's
  # mismatch here). GAS+EQ, G(GAS) and G(GAS+EQ) are Table 2's (bench/asr/run_table2.sh).
  asr_train_sets="clean real gas gas_gsr_eq gas_ext ctl_t60x0.33"
  asr_dose="real ctl_t60x0.33"
  case $demo_size in
    tiny) asr_corpus_opts="--utts-per-train-voice 2 --utts-per-test-voice 2"
          asr_train_opts="--epochs=1 --conv-layers=1 --conv-channels=8 --rnn-layers=1 --rnn-hidden=8 --batch-size=4" ;;
    small) ;;
  esac
fi

. ./cmd.sh
. ./path.sh
if [ -n "${KALDI_ROOT:-}" ] && [ -f "$KALDI_ROOT/egs/wsj/s5/utils/parse_options.sh" ]; then
  . "$KALDI_ROOT/egs/wsj/s5/utils/parse_options.sh"
else
  . ./local/parse_options.sh
fi
[ $# -eq 0 ] || { echo "$0: unexpected arguments: $*" >&2; echo "$help_message" >&2; exit 1; }
case $demo in true|false) ;; *) echo "$0: --demo must be true or false" >&2; exit 1 ;; esac
case $demo_size in small|tiny) ;; *) echo "$0: --demo-size must be small or tiny, got '$demo_size'" >&2; exit 1 ;; esac

# Absolute paths: lists and wav.scp pipes must work from any directory (Kaldi runs them from
# its own recipe directory in stage 8).
mkdir -p "$data" "$exp" "$(dirname "$results")"
data=$(readlink -f "$data"); exp=$(readlink -f "$exp"); results=$(readlink -f "$(dirname "$results")")/$(basename "$results")
corpus_dir=$(readlink -m "$corpus_dir")
librispeech_dir=$(readlink -m "${librispeech_dir:-$corpus_dir/LibriSpeech}")
but_dir=$(readlink -m "${but_dir:-$corpus_dir/BUT_ReverbDB}")
shared_data=$(readlink -m "$shared_data")
if [ "$demo" = true ]; then train_set=train_clean; else train_set=train_clean_460; fi
rirs=$data/rirs
conf=$(readlink -f ../../conf)   # the programs' settings as in the paper (conf/<program>.conf)

# Stage 8's recogniser, decided (and logged below) before any stage runs. The demo promises
# embedded data and no downloads, also in a Kaldi user's shell where KALDI_ROOT is exported: it
# uses the proxy unless --asr kaldi is asked, and Kaldi then builds its LM offline from the demo's
# own training transcripts (run_asr.sh --lm-text) instead of downloading openslr's.
if [ -z "$asr" ]; then
  if [ "$demo" = true ]; then asr=proxy; elif [ -n "${KALDI_ROOT:-}" ]; then asr=kaldi; else asr=skip; fi
fi
demo_lm_text=""
if [ "$demo" = true ] && [ "$asr" = kaldi ] && [[ " $kaldi_opts " != *" --lm-text "* ]]; then
  demo_lm_text=$exp/kaldi/lm_text.txt   # written at stage 8 from $data/$train_set/text
  kaldi_opts="$kaldi_opts --lm-text $demo_lm_text"
fi
case $asr in
  proxy) asr_plan="the proxy recogniser (asr-train/asr-decode; no Kaldi, no downloads)" ;;
  kaldi) asr_plan="Kaldi (local/kaldi/run_asr.sh)"
         if [ -n "$demo_lm_text" ]; then
           asr_plan="Kaldi (local/kaldi/run_asr.sh, LM built offline from the demo's transcripts: --lm-text $demo_lm_text)"
         fi ;;
  skip) asr_plan="nothing (KALDI_ROOT is not set; --asr proxy runs the proxy recogniser)" ;;
  *) echo "$0: --asr must be kaldi or proxy, got '$asr'" >&2; exit 1 ;;
esac

# ---- helpers ----
t_stage=$SECONDS
log() { echo "run.sh: $*" >&2; }
begin_stage() { t_stage=$SECONDS; log "stage $1: $2"; }
end_stage() { log "stage $1 done ($(( SECONDS - t_stage )) s): $2"; }
die() { echo "run.sh: ERROR: $*" >&2; exit 1; }
# A step is done when its marker holds the same signature (the settings it ran with).
is_done() { [ -f "$1" ] && [ "$(cat "$1")" = "$2" ]; }
mark_done() { { printf '%s\n' "$2" >"$1.tmp" && mv "$1.tmp" "$1"; } || die "cannot write the stage marker $1"; }
# The bytes of whichever of the files exist (a stage signature's ingredients); never fails, so a
# missing file cannot end the script silently under `set -e -o pipefail` inside "$(...)".
content_of() { local f; for f in "$@"; do if [ -f "$f" ]; then cat "$f"; fi; done; return 0; }
# The files tsrir wrote into a directory (its .tsrir-owned marker lists them), never a user's.
remove_tsrir_files() { local/remove_tsrir_files.sh "$@"; }
require() { for f in "$@"; do [ -s "$f" ] || die "missing input $f (run the earlier stages first)"; done; }
need_program() {
  for p in "$@"; do
    command -v "$p" >/dev/null || die "program $p not found on PATH (TSRIR_BIN=$TSRIR_BIN): build the toolkit first (utils/bootstrap.sh)"
  done
}
run_logged() {  # [JOB=1:N] <log> <command...>: through $run_cmd (default $train_cmd), Kaldi's
  local spec=() l                                   # argument order; on failure shows the log's tail
  if [[ "$1" =~ ^[A-Za-z_][A-Za-z0-9_]*=[0-9]+(:[0-9]+)?$ ]]; then spec=("$1"); shift; fi
  l=$1; shift
  # A program that runs threads asks the queue for that many slots, as Kaldi's scripts do
  # (queue.pl/slurm.pl: --num-threads N; run.pl records it).
  local threads=() a prev=""
  for a in "$@"; do
    case $a in --num-threads=*) threads=(--num-threads "${a#--num-threads=}") ;; esac
    [ "$prev" = --num-threads ] && threads=(--num-threads "$a")
    prev=$a
  done
  if ! ${run_cmd:-$train_cmd} ${threads[@]+"${threads[@]}"} ${spec[@]+"${spec[@]}"} "$l" "$@"; then
    # The log of the first failed job (run.pl's footer records each job's exit code).
    local shown; shown=$(grep -l '^# Ended (code [1-9]' ${l//JOB/*} 2>/dev/null | head -n 1 || true)
    tail -n 20 "${shown:-${l//JOB/1}}" >&2 || true
    die "failed: $* (log: $l)"
  fi
}
count() { if [ -f "$1" ]; then grep -c . "$1" || true; else echo 0; fi; }
set_label() {
  case $1 in
    real) echo real ;; gas) echo GAS ;; gas_eq) echo GAS+EQ ;; gas_gsr) echo "G(GAS)" ;;
    gas_eq_gsr) echo "G(GAS+EQ)" ;; gas_gsr_eq) echo "G(GAS)+EQ" ;; clean) echo "clean" ;;
    gas_ext) echo "GAS-ext" ;;
    ctl_*) echo "control ${1#ctl_}" ;;
    *) die "unknown RIR set name '$1'" ;;
  esac
}
# RESULTS.md = the header and whichever of Table 1 (stage 6) and Table 2 (stage 8) exist, so that
# re-running a stage replaces its table instead of appending.
write_results() {
  cat "$exp/results_header.md" $( [ -f "$exp/table1/section.md" ] && echo "$exp/table1/section.md") \
    $( [ -f "$exp/table2/section.md" ] && echo "$exp/table2/section.md") >"$results.tmp"
  mv "$results.tmp" "$results"
}
check_data_dir() { local/check_data_dir.sh "$1" || die "$1 is not a valid Kaldi data dir"; }

log "$( [ "$demo" = true ] && echo "demo ($demo_size)" || echo "full experiment"): stages $stage..$stop_stage, data=$data exp=$exp"
log "stage 8 uses $asr_plan"

# ---------------------------------------------------------------------------------------------
if [ $stage -le 0 ] && [ $stop_stage -ge 0 ]; then
  if [ "$demo" = true ]; then
    begin_stage 0 "embedded demo corpus (speech, RIRs, noise)"
    sig="size=$demo_size shared=$shared_data:$(for p in speech rirs/r3vival noise; do if [ -e "$shared_data/$p" ]; then printf '%s,' "$p"; fi; done) standin=$standin_model seed=$seed"
    if is_done "$data/local/demo_corpus/.done" "$sig"; then
      log "stage 0: demo corpus already made"
    else
      local/make_demo_data.sh --size "$demo_size" --shared-data "$shared_data" --standin-model "$standin_model" \
        --seed "$seed" "$data/local/demo_corpus"
      mark_done "$data/local/demo_corpus/.done" "$sig"
    fi
    while read -r line; do log "stage 0:   $line"; done <"$data/local/demo_corpus/SOURCES"
    end_stage 0 "$(cat "$data"/local/demo_corpus/speech/*/wav.scp | wc -l) utterances, $(count "$data/local/demo_corpus/rirs/rir.scp") RIRs, $(count "$data/local/demo_corpus/noise/noise.scp") noises"
  else
    begin_stage 0 "LibriSpeech ($librispeech_parts) and BUT ReverbDB"
    for part in $librispeech_parts; do
      if [ -d "$librispeech_dir/$part" ]; then
        log "stage 0: $librispeech_dir/$part present, not downloading"
      else
        [ "$(basename "$librispeech_dir")" = LibriSpeech ] ||
          die "$librispeech_dir/$part is missing; downloads unpack into <dir>/LibriSpeech, so --librispeech-dir must end in LibriSpeech"
        local/download_and_untar.sh "$(dirname "$librispeech_dir")" "$librispeech_url/$part.tar.gz"
        [ -d "$librispeech_dir/$part" ] || die "$librispeech_url/$part.tar.gz did not unpack into $librispeech_dir/$part"
      fi
    done
    if [ -d "$but_dir" ] && [ -n "$(find "$but_dir" -name env_meta.txt -print -quit)" ]; then
      log "stage 0: BUT ReverbDB present in $but_dir, not downloading"
    else
      local/download_and_untar.sh "$but_dir" "$but_url"
      [ -n "$(find "$but_dir" -name env_meta.txt -print -quit)" ] || die "$but_url unpacked into $but_dir holds no env_meta.txt"
    fi
    end_stage 0 "corpora in $librispeech_dir and $but_dir"
  fi
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 1 ] && [ $stop_stage -ge 1 ]; then
  begin_stage 1 "Kaldi data dirs, real RIR and noise lists, train/dev/test RIR split"
  need_program validate-data-dir
  if [ "$demo" = true ]; then
    corpus=$data/local/demo_corpus
    require "$corpus/.done"
    for set in train_clean dev_clean test_clean; do
      local/make_data_dir.sh "$corpus/speech/$set" "$data/$set"
      check_data_dir "$data/$set"
    done
    rir_source=$corpus/rirs
    noise_scp=$corpus/noise/noise.scp
    source_sig=$(cat "$corpus/.done")
  else
    for part in $librispeech_parts; do
      d=$data/$(echo "$part" | tr - _)
      sig="$librispeech_dir/$part"
      if is_done "$d/.done" "$sig"; then log "stage 1: $d already prepared"; continue; fi
      local/prepare_librispeech.sh "$librispeech_dir/$part" "$d"
      check_data_dir "$d"
      mark_done "$d/.done" "$sig"
    done
    if [[ " $librispeech_parts " == *" train-clean-100 "* ]] && [[ " $librispeech_parts " == *" train-clean-360 "* ]]; then
      local/combine_data_dirs.sh "$data/$train_set" "$data/train_clean_100" "$data/train_clean_360"
      check_data_dir "$data/$train_set"
    fi
    sig="$but_dir skip=$but_skip_rooms"
    if ! is_done "$data/local/but/.done" "$sig"; then
      local/prepare_but_reverbdb.sh --skip-rooms "$but_skip_rooms" "$but_dir" "$data/local/but"
      mark_done "$data/local/but/.done" "$sig"
    fi
    rir_source=$data/local/but
    noise_scp=$data/local/but/noise.scp
    source_sig=$(cat "$data/local/but/.done")
  fi
  require "$rir_source/meta.txt" "$rir_source/rir.scp" "$noise_scp"
  # The real RIRs: all of them, and the seeded split into train/dev/test.
  mkdir -p "$rirs/real_all"
  cp "$rir_source/meta.txt" "$rirs/real_all/meta.txt"
  awk '{print $1}' "$rir_source/meta.txt" | sort >"$rirs/real_all/ids"
  local/subset_rir_set.sh --meta "$rir_source/meta.txt" "$rirs/real_all/ids" "$rir_source" "$rirs/real_all"
  local/split_rirs.sh --seed "$seed" --sizes "$split_sizes" --group-fields "$split_group_fields" "$rirs/real_all/meta.txt" "$rirs/split"
  # Each set's .done identifies its content (the audio behind unchanged paths can change, e.g. the
  # demo's stand-ins), so that the later stages redo what depends on it.
  for split in train dev test; do
    local/subset_rir_set.sh "$rirs/split/$split.ids" "$rirs/real_all" "$rirs/real_$split"
    mark_done "$rirs/real_$split/.done" "real: $source_sig $(cat "$rirs/split/split.txt") $(md5sum <"$rirs/real_$split/rir.scp")"
  done
  # Noise: background noise usable with any RIR (Kaldi noise_list format).
  mkdir -p "$data/noise"
  awk '{print "--noise-id " $1 " --noise-type point-source --bg-fg-type background " $2}' "$noise_scp" \
    >"$data/noise/noise_list"
  end_stage 1 "$(for s in $train_set dev_clean test_clean; do [ -f "$data/$s/utt2spk" ] && printf '%s: %s utts; ' "$s" "$(count "$data/$s/utt2spk")"; done)real RIRs $(cat "$rirs/split/split.txt"); $(count "$data/noise/noise_list") noises"
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 2 ] && [ $stop_stage -ge 2 ]; then
  begin_stage 2 "GAS: one synthetic RIR per real RIR (rir-simulate --model=$sim_model, random absorption $absorption_range per $absorption_draw)"
  need_program rir-room-list rir-simulate
  require "$rirs/real_all/meta.txt" "$rirs/split/train.ids"
  sig="model=$sim_model absorption=$absorption_range/$absorption_draw seed=$seed $(md5sum <"$rirs/real_all/meta.txt") $(md5sum <"$conf/rir-simulate.conf")"
  out=$rirs/gas_all
  if is_done "$out/.done" "$sig"; then
    log "stage 2: GAS RIRs already simulated"
  else
    # Only what this stage writes goes (a user's file in $out stays; docs/robustness.md).
    rm -rf "$out/split$nj" "$out/log"; rm -f "$out/setups.txt" "$out/room_list" "$out/rir.scp" "$out/rir_list"
    mkdir -p "$out/split$nj"
    # The metadata table (rir-id room-id Lx Ly Lz sx sy sz mx my mz) -> one room-list line per RIR
    # with random absorption, seeded by (seed, rir id) (TS-RIR sec. 3.3: "random surface
    # absorption/reflection coefficients ... because we do not have room-material information").
    { echo "rir-id room-id Lx Ly Lz sx sy sz mx my mz"; cat "$rirs/real_all/meta.txt"; } >"$out/setups.txt"
    run_logged "$out/log/room_list.log" rir-room-list --format=table --seed="$seed" \
      --absorption-range="$absorption_range" --absorption-draw="$absorption_draw" "$out/setups.txt" "$out/room_list"
    n=$(grep -vc '^#' "$out/room_list" || true)
    jobs=$(( n < nj ? n : nj ))
    # Round-robin split; rir-simulate's randomness is keyed by (seed, rir id), so the split does
    # not change any RIR.
    for ((j = 1; j <= jobs; j++)); do
      grep -v '^#' "$out/room_list" | awk -v j="$j" -v n="$jobs" '(NR - 1) % n == j - 1' >"$out/split$nj/room_list.$j"
    done
    run_logged JOB=1:$jobs "$out/log/simulate.JOB.log" rir-simulate --config="$conf/rir-simulate.conf" --model="$sim_model" --seed="$seed" \
      --num-threads=1 "$out/split$nj/room_list.JOB" "$out/split$nj/JOB"
    cat "$out"/split$nj/*/rir.scp | sort >"$out/rir.scp"
    cat "$out"/split$nj/*/rir_list | sort -k2,2 >"$out/rir_list"
    [ "$(count "$out/rir.scp")" -eq "$n" ] || die "rir-simulate wrote $(count "$out/rir.scp") of $n RIRs (logs: $out/log)"
    mark_done "$out/.done" "$sig"
  fi
  for split in train dev test; do
    local/subset_rir_set.sh "$rirs/split/$split.ids" "$out" "$rirs/gas_$split"
    mark_done "$rirs/gas_$split/.done" "gas: $sig $(md5sum <"$rirs/gas_$split/rir.scp")"
  done
  end_stage 2 "$(count "$out/rir.scp") GAS RIRs in $out (logs: $out/log)"
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 3 ] && [ $stop_stage -ge 3 ]; then
  begin_stage 3 "sub-band EQ fitted on the $(count "$rirs/real_train/rir.scp") real training RIRs (rir-eq fit $eq_opts)"
  need_program rir-eq
  require "$rirs/real_train/rir_list"
  sig="$eq_opts $(content_of "$rirs/real_train/.done") $(md5sum <"$conf/rir-eq.conf")"
  if is_done "$exp/eq/.done" "$sig"; then
    log "stage 3: EQ model already fitted"
  else
    # shellcheck disable=SC2086
    run_logged "$exp/eq/log/fit.log" rir-eq fit --config="$conf/rir-eq.conf" $eq_opts --num-threads="$num_threads" \
      "$rirs/real_train/rir_list" "$exp/eq/eq.model"
    mark_done "$exp/eq/.done" "$sig"
  fi
  end_stage 3 "$exp/eq/eq.model (log: $exp/eq/log/fit.log)"
fi

# ---------------------------------------------------------------------------------------------
gan_dir=${gan_model:-$exp/tsrirgan}
if [ $stage -le 4 ] && [ $stop_stage -ge 4 ]; then
  if [ -n "$gan_model" ]; then
    begin_stage 4 "TS-RIRGAN: using the given model $gan_model"
    [ -e "$gan_model" ] || die "--gan-model $gan_model does not exist"
    end_stage 4 "no training"
  else
    begin_stage 4 "TS-RIRGAN training (steps $gan_steps, width $gan_width, batch $gan_batch_size, $gan_device)"
    need_program ts-rirgan-train
    require "$rirs/real_train/rir_list" "$rirs/gas_train/rir_list"
    # The settings a model trained now would store (--print-settings: every option's value, the
    # program's defaults included), so that new defaults train the model anew.
    # shellcheck disable=SC2086
    settings=$(ts-rirgan-train --real="$rirs/real_train/rir_list" --synthetic="$rirs/gas_train/rir_list" \
      --width="$gan_width" --batch-size="$gan_batch_size" --seed="$seed" $gan_opts --print-settings "$gan_dir" | md5sum) ||
      die "ts-rirgan-train --print-settings failed"
    sig="steps=$gan_steps width=$gan_width batch=$gan_batch_size opts=$gan_opts seed=$seed threads=${gan_num_threads:-$num_threads} settings=${settings%% *} $(content_of "$rirs/real_train/.done" "$rirs/gas_train/.done" | md5sum)"
    if is_done "$gan_dir/.done" "$sig"; then
      log "stage 4: TS-RIRGAN already trained"
    else
      resume=()
      # An interrupted run with the same settings continues from its checkpoint.
      # The settings it runs with sit beside the model dir: the dir itself holds only what
      # ts-rirgan-train writes (its .tsrir-owned marker lists them; docs/robustness.md).
      if [ -f "$gan_dir/checkpoint.pt" ] && [ -f "$gan_dir.settings" ] && [ "$(cat "$gan_dir.settings")" = "$sig" ]; then
        resume=(--resume); log "stage 4: resuming from $gan_dir/checkpoint.pt"
      else
        # A fresh start: only the files training writes go (never anything else in the dir).
        rm -f "$gan_dir/checkpoint.pt" "$gan_dir/generator-g_real.pt" "$gan_dir/generator-g_synthetic.pt" \
          "$gan_dir/settings.txt" "$gan_dir/loss_log.csv" "$gan_dir/.done"
        printf '%s\n' "$sig" >"$gan_dir.settings"
      fi
      run_cmd=$gan_cmd run_logged "$exp/log/tsrirgan_train.log" ts-rirgan-train --real="$rirs/real_train/rir_list" \
        --synthetic="$rirs/gas_train/rir_list" --steps="$gan_steps" --width="$gan_width" \
        --batch-size="$gan_batch_size" --seed="$seed" --num-threads="${gan_num_threads:-$num_threads}" --device="$gan_device" \
        $gan_opts ${resume[@]+"${resume[@]}"} "$gan_dir"
      mark_done "$gan_dir/.done" "$sig"
    fi
    end_stage 4 "$gan_dir (log: $exp/log/tsrirgan_train.log; losses: $gan_dir/loss_log.csv)"
  fi
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 5 ] && [ $stop_stage -ge 5 ]; then
  begin_stage 5 "RIR sets GAS+EQ, G(GAS), G(GAS+EQ), G(GAS)+EQ for the train and test splits"
  need_program rir-eq gas-to-real
  require "$exp/eq/eq.model"
  [ -e "$gan_dir" ] || die "missing TS-RIRGAN model $gan_dir (run stage 4 or give --gan-model)"
  gan_sig=$( [ -f "$gan_dir/.done" ] && cat "$gan_dir/.done" || ls -l --time-style=+%s "$gan_dir" | md5sum)
  # <set> <operation> <input set>: eq = rir-eq apply, gsr = gas-to-real (G_SR).
  for split in train test; do
    for spec in "gas_eq eq gas" "gas_gsr gsr gas" "gas_eq_gsr gsr gas_eq" "gas_gsr_eq eq gas_gsr"; do
      read -r set op input <<<"$spec"
      in=$rirs/${input}_$split; out=$rirs/${set}_$split
      require "$in/rir_list"
      # The input set's identity (its .done, which chains back to the real RIRs) and the model's.
      if [ "$op" = eq ]; then model_sig="$(content_of "$exp/eq/.done") $(md5sum <"$conf/rir-eq-apply.conf")"; else model_sig=$gan_sig; fi
      sig="$op seed=$seed $(content_of "$in/.done" | md5sum) $model_sig"
      if is_done "$out/.done" "$sig"; then continue; fi
      if [ "$op" = eq ]; then
        run_logged "$exp/log/make_${set}_$split.log" rir-eq apply --config="$conf/rir-eq-apply.conf" --seed="$seed" --num-threads="$num_threads" \
          "$exp/eq/eq.model" "$in/rir_list" "$out"
      else
        # 16-bit output: Kaldi's own wav-reverberate reads 16-bit PCM only.
        run_logged "$exp/log/make_${set}_$split.log" gas-to-real --model="$gan_dir" --format=int16 \
          --num-threads="${gan_num_threads:-$num_threads}" --device="$gan_device" "$in/rir_list" "$out"
      fi
      [ "$(count "$out/rir.scp")" -eq "$(count "$in/rir.scp")" ] || die "$out has $(count "$out/rir.scp") RIRs, $in has $(count "$in/rir.scp")"
      mark_done "$out/.done" "$sig"
      log "stage 5:   $(set_label "$set") ($split): $(count "$out/rir.scp") RIRs in $out"
    done
  done
  # GAS-ext: rir-diagnose tests the real training RIRs against their GAS set-ups (stage 2's room
  # list: same positions and random absorption) for the effects of its catalog and fits the model
  # extension of each detected one per room (decided on half of the RIRs, judged on the other half);
  # rir-simulate then renders every set-up of the train and test splits with its room's extended
  # model. The set differs from GAS only by what the diagnosis found.
  # Positive controls for stage 8 (ctl_* among the proxy's training sets): the real training RIRs
  # with one known mismatch each (rir-perturb; docs/results/downstream.md).
  for set in ${asr_train_sets:-$train_sets}; do
    case $set in ctl_t60x*) opt="--t60-scale=${set#ctl_t60x}" ;; ctl_drr*) opt="--drr-offset-db=${set#ctl_drr}" ;;
                 ctl_lf*) opt="--lf-ringing-db=${set#ctl_lf}" ;; *) continue ;; esac
    need_program rir-perturb
    out=$rirs/${set}_train
    sig="$opt seed=$seed $(content_of "$rirs/real_train/.done" | md5sum)"
    if is_done "$out/.done" "$sig"; then continue; fi
    run_logged "$exp/log/make_${set}_train.log" rir-perturb $opt --seed="$seed" --num-threads="$num_threads" \
      "$rirs/real_train/rir_list" "$out"
    mark_done "$out/.done" "$sig"
    log "stage 5:   $(set_label "$set") (train): $(tail -n 1 "$exp/log/make_${set}_train.log" | sed 's/^rir-perturb: perturbed //; s/ into .*//')"
  done
  if [[ " $rir_sets $train_sets " == *" gas_ext "* ]]; then
    need_program rir-diagnose rir-simulate
    require "$rirs/gas_all/room_list" "$rirs/real_train/rir_list"
    diag=$exp/diagnose
    sig="model=$sim_model seed=$seed $(content_of "$rirs/real_train/.done" "$rirs/gas_all/.done" | md5sum)"
    if is_done "$diag.done" "$sig"; then
      log "stage 5:   rir-diagnose already ran ($diag)"
    else
      rm -f "$diag.done"
      run_logged "$exp/log/diagnose.log" rir-diagnose --fs=16000 --model="$sim_model" --seed="$seed" \
        --num-threads="$num_threads" "$rirs/gas_all/room_list" "$rirs/real_train/rir_list" "$diag"
      mark_done "$diag.done" "$sig"
    fi
    require "$diag/extended_models"
    while read -r room spec; do log "stage 5:   extended model of room $room: $spec"; done <"$diag/extended_models"
    out=$rirs/gas_ext_all
    sig="$(cat "$diag.done") $(md5sum <"$diag/extended_models") $(md5sum <"$rirs/gas_all/room_list") $(md5sum <"$conf/rir-simulate.conf")"
    if is_done "$out/.done" "$sig"; then
      log "stage 5:   GAS-ext RIRs already simulated"
    else
      rm -rf "$out/rooms" "$out/log"; rm -f "$out/rir.scp" "$out/rir_list" "$out/.done"
      mkdir -p "$out/rooms"
      # One rir-simulate run per room (each room has its own extended model). A room without
      # training RIRs has no fitted model: it keeps the baseline, and the log says so.
      awk '{ for (i = 2; i <= NF; i++) if ($i ~ /^room-id=/) { r = substr($i, 9); print > (dir "/" r ".room_list") } }' \
        dir="$out/rooms" <(grep -v '^#' "$rirs/gas_all/room_list")
      for rl in "$out"/rooms/*.room_list; do
        room=$(basename "$rl" .room_list)
        spec=$(awk -v r="$room" '$1 == r { print $2 }' "$diag/extended_models")
        [ -n "$spec" ] || { spec=$sim_model; log "stage 5:   room $room has no training RIRs: GAS-ext = $sim_model there"; }
        # Float samples: the transducer extension carries the measured chain's gain (~18 dB on
        # R3VIVAL), which can pass 16-bit full scale; the toolkit's wav-reverberate reads float.
        run_logged "$out/log/simulate.$room.log" rir-simulate --config="$conf/rir-simulate.conf" --model="$spec" \
          --seed="$seed" --format=float --num-threads="$num_threads" "$rl" "$out/rooms/$room"
      done
      cat "$out"/rooms/*/rir.scp | sort >"$out/rir.scp"
      cat "$out"/rooms/*/rir_list | sort -k2,2 >"$out/rir_list"
      [ "$(count "$out/rir.scp")" -eq "$(count "$rirs/gas_all/rir.scp")" ] ||
        die "GAS-ext has $(count "$out/rir.scp") RIRs, GAS $(count "$rirs/gas_all/rir.scp") (logs: $out/log)"
      mark_done "$out/.done" "$sig"
    fi
    for split in train test; do
      local/subset_rir_set.sh "$rirs/split/$split.ids" "$out" "$rirs/gas_ext_$split"
      mark_done "$rirs/gas_ext_$split/.done" "gas_ext: $sig $(md5sum <"$rirs/gas_ext_$split/rir.scp")"
    done
    log "stage 5:   GAS-ext: $(count "$rirs/gas_ext_train/rir.scp") train, $(count "$rirs/gas_ext_test/rir.scp") test RIRs in $rirs/gas_ext_{train,test} (diagnosis: $diag/report.html)"
  fi
  end_stage 5 "$(for s in $rir_sets; do printf '%s ' "$(set_label "$s")"; done)for train and test in $rirs"
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 6 ] && [ $stop_stage -ge 6 ]; then
  begin_stage 6 "Table 1: mean T60, DRR, EDT, C50 (CTE) of each test-split set vs the real test RIRs (rir-metrics --definition=$metrics_definition)"
  need_program rir-metrics
  t1=$exp/table1
  rm -rf "$t1/sets"; rm -f "$t1/table1.txt" "$t1/rir-metrics.log" "$t1/section.md"; mkdir -p "$t1/sets"
  require "$rirs/real_test/rir.scp"
  cp "$rirs/real_test/rir.scp" "$t1/sets/real"
  labels=()
  for s in $rir_sets; do
    require "$rirs/${s}_test/rir.scp"
    l=$(set_label "$s"); cp "$rirs/${s}_test/rir.scp" "$t1/sets/$l"; labels+=("$l")
  done
  # Run from the sets directory so that the table's row names are the paper's set names.
  (cd "$t1/sets" && rir-metrics --config="$conf/rir-metrics.conf" --definition="$metrics_definition" --num-threads="$num_threads" \
      --reference=real "${labels[@]}") >"$t1/table1.txt" 2>"$t1/rir-metrics.log" ||
    { cat "$t1/rir-metrics.log" >&2; die "rir-metrics failed (log: $t1/rir-metrics.log)"; }
  {
    echo "# librispeech_farfield results"
    echo
    echo "$( [ "$demo" = true ] && echo "Demo run ($demo_size)" || echo "Full run"), $(date -u +%Y-%m-%d), seed $seed; real RIRs: $(cat "$rirs/split/split.txt")."
    if [ "$demo" = true ]; then
      echo
      echo "Data of this demo run (stand-ins are marked STAND-IN):"
      sed 's/^/- /' "$data/local/demo_corpus/SOURCES"
      echo "- TS-RIRGAN: width $gan_width, $gan_steps steps (the paper's model: width 64, trained to convergence), so the G(...) rows come from a barely trained translator"
    fi
  } >"$exp/results_header.md"
  {
    echo
    echo "## Table 1: acoustic parameters of the RIR sets (test split) vs the real test RIRs"
    echo
    echo '```'
    cat "$t1/table1.txt"
    echo '```'
  } >"$t1/section.md"
  write_results
  cat "$t1/table1.txt"
  end_stage 6 "Table 1 in $results"
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 7 ] && [ $stop_stage -ge 7 ]; then
  begin_stage 7 "far-field data dirs (reverberate-data, SNR $snrs dB, noise at a random offset, looped)"
  need_program reverberate-data wav-reverberate wav-to-duration
  require "$data/noise/noise_list"
  made=()
  farfield() {  # <in-dir> <rir-list> <out-dir>
    local in=$1 rir_list=$2 out=$3 sig wavs=()
    require "$in/wav.scp" "$rir_list"
    # Durations once per clean dir (the recipe's own stage-1 output), as Kaldi's get_reco2dur.sh
    # does: every far-field set made from it then reads them instead of opening each recording.
    if [ ! -s "$in/reco2dur" ] || [ "$(count "$in/reco2dur")" -ne "$(count "$in/wav.scp")" ]; then
      run_logged "$exp/log/reco2dur_$(basename "$in").log" wav-to-duration "scp:$in/wav.scp" "ark,t:$in/reco2dur"
    fi
    sig="snrs=$snrs seed=$seed wavs=$write_wavs $(content_of "$in/wav.scp" "$rir_list" "$(dirname "$rir_list")/.done" "$data/noise/noise_list" "$conf/reverberate.conf" | md5sum)"
    local name; name=$(basename "$out")
    if ! is_done "$exp/farfield/$name.done" "$sig"; then
      [ "$write_wavs" = true ] && wavs=(--write-wavs "$data/wav/$name")
      run_logged "$exp/log/reverberate_$name.log" reverberate-data --config="$conf/reverberate.conf" \
        --rir-set-parameters "1.0, $rir_list" --noise-set-parameters "$data/noise/noise_list" \
        --background-snrs "$snrs" --random-seed "$seed" --num-threads "$num_threads" ${wavs[@]+"${wavs[@]}"} "$in" "$out"
      check_data_dir "$out"
      # Pipes regenerate the audio: wavs of an earlier --write-wavs run would be stale.
      [ "$write_wavs" = true ] || remove_tsrir_files "$data/wav/$name"
      mkdir -p "$exp/farfield"
      mark_done "$exp/farfield/$name.done" "$sig"
    fi
    made+=("$(basename "$out") ($(count "$out/wav.scp") recordings)")
  }
  for s in $train_sets; do
    [ "$s" = clean ] && continue
    farfield "$data/$train_set" "$rirs/${s}_train/rir_list" "$data/${train_set}_rvb_$s"
  done
  farfield "$data/dev_clean" "$rirs/real_dev/rir_list" "$data/dev_clean_rvb_real"
  farfield "$data/test_clean" "$rirs/real_test/rir_list" "$data/test_clean_rvb_real"
  end_stage 7 "${made[*]} in $data, each valid (validate-data-dir$( [ -n "${KALDI_ROOT:-}" ] && echo " and Kaldi's validate_data_dir.sh --no-feats"))"
fi

# ---------------------------------------------------------------------------------------------
if [ $stage -le 8 ] && [ $stop_stage -ge 8 ]; then
  case $asr in
    skip)
      begin_stage 8 "Table 2"
      log "stage 8: KALDI_ROOT is not set: skipping Kaldi training (set it to a compiled Kaldi and rerun with --stage 8, or use --asr proxy)"
      ;;
    kaldi)
      if [[ " $kaldi_opts " == *" --stop-after gmm "* ]]; then
        begin_stage 8 "Kaldi GMM (mono, tri1, tri2b) training and decoding per training set"
      else
        begin_stage 8 "Kaldi chain TDNN training and decoding per training set, Table 2"
      fi
      [ -n "${KALDI_ROOT:-}" ] || die "stage 8 --asr kaldi: KALDI_ROOT is not set (set it to a compiled Kaldi, or use --asr proxy)"
      if [ -n "$demo_lm_text" ]; then
        require "$data/$train_set/text"
        mkdir -p "$(dirname "$demo_lm_text")"
        cut -d' ' -f2- "$data/$train_set/text" >"$demo_lm_text"
      fi
      for s in $train_sets; do
        if [ "$s" = clean ]; then tr=$data/$train_set; else tr=$data/${train_set}_rvb_$s; fi
        require "$tr/wav.scp" "$data/test_clean_rvb_real/wav.scp" "$data/dev_clean_rvb_real/wav.scp"
        # shellcheck disable=SC2086  # $kaldi_opts: options, split on blanks
        local/kaldi/run_asr.sh --stage "$kaldi_stage" --nj "$nj" --decode-nj "$nj" --lm-url "$lm_url" \
          --lm-dir "$exp/kaldi/lm" --train "$tr" --dev "$data/dev_clean_rvb_real" --test "$data/test_clean_rvb_real" \
          $kaldi_opts "$exp/kaldi/$s"
      done
      if [[ " $kaldi_opts " == *" --stop-after gmm "* ]]; then
        # GMMs only: run_asr.sh's best WER/CER per model and test set (exp/gmm_results.txt)
        for s in $train_sets; do require "$exp/kaldi/$s/exp/gmm_results.txt"; done
        table2=$(for s in $train_sets; do sed "s|^|    $s |" "$exp/kaldi/$s/exp/gmm_results.txt"; done)
        title="Kaldi GMMs (run_asr.sh --stop-after gmm): best WER and CER (%) per training set, model and test set"
      else
        table2=$(local/collect_wer.sh --sets "$train_sets" --test-set test_farfield "$exp/kaldi") ||
          die "local/collect_wer.sh could not collect the WERs of $exp/kaldi (see the messages above)"
        title="WER (%) on the real far-field test set (test-clean ⊛ real test RIRs + noise)"
      fi
      ;;
    proxy)
      begin_stage 8 "proxy recogniser (asr-train/asr-decode) per training set and seed ($asr_seeds), Table 2"
      need_program asr-train asr-decode reverberate-data
      # The real-speech test set reads ../shared/data/speech in place (skipped when absent).
      proxy_opts=(--train-sets "${asr_train_sets:-$train_sets}" --seeds "$asr_seeds" --snrs "$snrs" --num-threads "$asr_num_threads"
                  --jobs "$asr_jobs" --nj "$nj" --train-config "$(readlink -f "$asr_train_config")"
                  --train-copies "$asr_train_copies" --dose "$asr_dose" --real-speech "$shared_data/speech")
      [ -n "$asr_corpus_opts" ] && proxy_opts+=(--corpus-opts "$asr_corpus_opts")
      [ -n "$asr_train_opts" ] && proxy_opts+=(--train-opts "$asr_train_opts")
      table2=$(local/asr/run_proxy.sh "${proxy_opts[@]}" "$rirs" "$data/noise/noise_list" "$data" "$exp") ||
        die "stage 8 proxy failed (logs: $exp/asr/log)"
      title="CER and WER (%) of the proxy recogniser on test speech ⊛ held-out real test RIRs + real noise (local/asr/run_proxy.sh)"
      ;;
    *) die "--asr must be kaldi or proxy, got '$asr'" ;;
  esac
  if [ "$asr" != skip ]; then
  mkdir -p "$exp/table2"
  {
    echo
    echo "## Table 2: $title"
    echo
    echo "$table2"
  } >"$exp/table2/section.md"
  [ -f "$exp/results_header.md" ] || echo "# librispeech_farfield results" >"$exp/results_header.md"
  write_results
  echo "$table2"
  fi
  end_stage 8 "results in $results"
fi
log "done: stages $stage..$stop_stage (total $SECONDS s)"
