#!/usr/bin/env bash
# Stage 8 of run.sh for one training set: the far-field LibriSpeech ASR benchmark of the paper
# (RoyJames/kaldi egs/librispeech/s5/run_rvb.sh + local/chain/tuning/run_tdnn_1d_custom.sh; see
# docs/reference/spec-digest.md sec. 5.3) run through Kaldi's own scripts in a Kaldi work
# directory <work-dir> (steps/ and utils/ of egs/wsj/s5, local/ of egs/librispeech/s5):
#   1 LMs (openslr 11) and lexicon, dict, lang_nosp, G.fst (tgsmall, tgmed), ConstArpa (tglarge, fglarge)
#   2 the far-field train, dev and test dirs copied in, 13-dim MFCC + CMVN
#   3 GMMs: mono (2k shortest), tri1 (5k, 2000/10000), tri2b LDA+MLLT (10k, 2500/15000),
#     tri3b SAT (10k, 2500/15000), tri4b SAT (4200/40000)
#   4 pronunciation and silence probabilities -> data/lang, its G.fst and ConstArpa LMs
#   5 tri5b SAT on the whole training set (5000/100000), then Kaldi's data cleanup -> tri5b_cleaned
#   6 speed perturbation, 40-dim hires MFCC (volume perturbed), PCA, 512-Gaussian diagonal UBM,
#     i-vector extractor, online i-vectors (training: 2 utterances per speaker)
#   7 chain TDNN-F (tdnn_1d: 16 tdnnf layers, 1536/160, 7000-leaf tree; 4 epochs; 2 -> 2 jobs)
#   8 decoding of the dev and test sets: tgsmall, rescored with tgmed, tglarge and fglarge, and
#     online decoding with the tgsmall graph
# Deviations from the paper's recipe, both forced by training on one far-field set: tri4b is
# trained on the first ~100 h (30k utterances; the paper: train-clean-100) and the cleanup uses
# Kaldi's steps/cleanup/clean_and_segment_data.sh directly.
#
# A corpus without LibriSpeech's LMs and lexicon, and no internet (docs/results/kaldi_gmm.md):
#   --lm-text <text>   stage 1 builds, instead of the openslr downloads, a word n-gram LM
#                      (--lm-order, Kneser-Ney: Kaldi's utils/lang/make_kn_lm.py) from <text> (one
#                      sentence a line, e.g. the training transcripts) and an espeak-ng lexicon
#                      (local/kaldi/make_espeak_dict.sh, voices --dict-voices) of every word of the
#                      LM text, of the train/dev/test transcripts and of --dict-text <text> (words
#                      for the lexicon only, e.g. a test set decoded elsewhere); all are lowercased
#                      (espeak-ng is case-blind). OOV word: <unk>. Decoding graph: lang_nosp_test_small.
#   --stop-after gmm   stage 3 stops after mono, tri1 and tri2b; each is decoded on the test set(s)
#                      (--test, --dev if given, --extra-tests) with steps/decode.sh and scored with
#                      steps/score_kaldi.sh and steps/scoring/score_kaldi_cer.sh; the best WER/CER per
#                      model and set (Kaldi's convention: best LM weight and insertion penalty) are
#                      written to <work-dir>/exp/gmm_results.txt; --dev is then optional.
#   --tri1-size, --tri2b-size  "<leaves> <Gaussians>" (or "<leaves>,<Gaussians>") of tri1 and tri2b
#                      (small corpora need fewer).
set -euo pipefail

stage=1
nj=8
decode_nj=8
train=""            # far-field training data dir (from run.sh stage 7)
dev=""              # far-field dev data dir
test=""             # far-field test data dir
lm_url=www.openslr.org/resources/11
lm_dir=""           # shared LM download dir (default: <work-dir>/../lm)
cleanup=true
use_gpu=yes         # steps/nnet3/chain/train.py --use-gpu (yes | wait | no)
num_jobs_initial=2  # the paper's run_tdnn_1d_custom.sh (upstream: 3)
num_jobs_final=2    # (upstream: 16)
lm_text=""          # text (one sentence a line) for a small LM + espeak-ng lexicon: no downloads
lm_order=3          # n-gram order of the --lm-text LM
dict_voices="en-us en-gb"  # espeak-ng voices of the --lm-text lexicon
stop_after=""       # gmm: stop after mono/tri1/tri2b training and their decoding
tri1_size="2000 10000"     # tri1 leaves and Gaussians
tri2b_size="2500 15000"    # tri2b leaves and Gaussians
extra_tests=""      # more test data dirs (space-separated) decoded with --stop-after gmm
dict_text=""        # more sentences whose words go into the --lm-text lexicon (not into the LM)
help_message="Usage: $0 [--stage N] [--nj N] --train <dir> --dev <dir> --test <dir> <kaldi-work-dir>
       $0 --lm-text <text> --stop-after gmm [--nj N] --train <dir> --test <dir> [--extra-tests <dirs>] <kaldi-work-dir>
e.g.: $0 --train data/train_clean_460_rvb_gas --dev data/dev_clean_rvb_real --test data/test_clean_rvb_real exp/kaldi/gas
      $0 --lm-text lm_text.txt --stop-after gmm --nj 2 --tri1-size \"200 1500\" --tri2b-size \"250 2000\" \\
        --train data/asr/train_gas --test data/asr/test_real --extra-tests data/asr/test_realspeech exp/kaldi_gmm/gas"

[ -n "${KALDI_ROOT:-}" ] || { echo "$0: KALDI_ROOT must point to a compiled Kaldi" >&2; exit 1; }
. "$KALDI_ROOT/egs/wsj/s5/utils/parse_options.sh"
[ $# -eq 1 ] || { echo "$help_message" >&2; exit 1; }
case $stop_after in ""|gmm) ;; *) echo "$0: --stop-after must be gmm or empty (got '$stop_after')" >&2; exit 1 ;; esac
for d in "$train" "$test" $extra_tests; do
  [ -n "$d" ] && [ -f "$d/wav.scp" ] || { echo "$0: --train, --test and --extra-tests must be data dirs (got '$d')" >&2; exit 1; }
done
if [ -n "$dev" ] || [ "$stop_after" != gmm ]; then
  [ -n "$dev" ] && [ -f "$dev/wav.scp" ] || { echo "$0: --dev must be a data dir (got '$dev')" >&2; exit 1; }
fi
tri1_size=${tri1_size//,/ }; tri2b_size=${tri2b_size//,/ }  # "300,2000" also (run.sh --kaldi-opts)
if [ -n "$lm_text" ]; then
  [ -s "$lm_text" ] || { echo "$0: --lm-text: empty or missing file '$lm_text'" >&2; exit 1; }
  lm_text=$(readlink -f "$lm_text")
fi
[ -z "$dict_text" ] || dict_text=$(readlink -f "$dict_text")
recipe=$(cd "$(dirname "$(readlink -f "$0")")/../.." && pwd)
w=$1
mkdir -p "$w"
w=$(readlink -f "$w")
lm_dir=$(readlink -m "${lm_dir:-$w/../lm}")
train=$(readlink -f "$train"); test=$(readlink -f "$test")
[ -z "$dev" ] || dev=$(readlink -f "$dev")
# the evaluation sets: Kaldi data dir name -> source dir
eval_names=(test_farfield); eval_dirs=("$test")
[ -z "$dev" ] || { eval_names+=(dev_farfield); eval_dirs+=("$dev"); }
for d in $extra_tests; do eval_names+=("$(basename "$d")"); eval_dirs+=("$(readlink -f "$d")"); done

# ---- the Kaldi work directory ----
cd "$w"
ln -sfn "$KALDI_ROOT/egs/wsj/s5/steps" steps
ln -sfn "$KALDI_ROOT/egs/wsj/s5/utils" utils
ln -sfn "$KALDI_ROOT/egs/librispeech/s5/local" local
mkdir -p conf data/local
cp "$recipe"/conf/mfcc.conf "$recipe"/conf/mfcc_hires.conf "$recipe"/conf/online_cmvn.conf conf/
# queue.pl and slurm.pl read conf/queue.conf / conf/slurm.conf relative to the directory they start
# from (this one): without the copy a cluster configuration would be silently ignored here.
for f in queue.conf slurm.conf; do
  if [ -f "$recipe/conf/$f" ]; then cp "$recipe/conf/$f" conf/; else rm -f "conf/$f"; fi
done
cat >path.sh <<EOF
export KALDI_ROOT=$KALDI_ROOT
. $recipe/path.sh
EOF
cp "$recipe/cmd.sh" cmd.sh
. ./cmd.sh
. ./path.sh

# Kaldi splits data per speaker: never more jobs than speakers.
jobs_for() { local s; s=$(wc -l <"$1/spk2utt"); echo $(( s < $2 ? s : $2 )); }
subset() {  # <src> <n> <dst> [--shortest]: at most n utterances
  local n; n=$(wc -l <"$1/utt2spk")
  if [ "$n" -le "$2" ]; then utils/copy_data_dir.sh "$1" "$3"; else utils/subset_data_dir.sh ${4:-} "$1" "$2" "$3"; fi
}

oov="<UNK>"; gmm_lang_test=data/lang_nosp_test_tgsmall; gmm_lm=tgsmall
[ -z "$lm_text" ] || { oov="<unk>"; gmm_lang_test=data/lang_nosp_test_small; gmm_lm=small; }
# data dir transcripts without utterance ids (lowercased)
transcripts() { for d in "$@"; do cut -d' ' -f2- "$d/text"; done | tr '[:upper:]' '[:lower:]'; }

if [ "$stage" -le 1 ] && [ -n "$lm_text" ]; then
  mkdir -p data/local/lm_small
  tr '[:upper:]' '[:lower:]' <"$lm_text" | awk 'NF' >data/local/lm_small/lm_text.txt
  { cat data/local/lm_small/lm_text.txt; transcripts "$train" "${eval_dirs[@]}"
    [ -z "$dict_text" ] || tr '[:upper:]' '[:lower:]' <"$dict_text"; } >data/local/lm_small/sentences.txt
  tr -s ' ' '\n' <data/local/lm_small/sentences.txt | grep -v '^$' | sort -u >data/local/lm_small/words.txt
  "$recipe/local/kaldi/make_espeak_dict.sh" --voices "$dict_voices" --oov "$oov" \
    --sentences data/local/lm_small/sentences.txt data/local/lm_small/words.txt data/local/dict_nosp
  utils/prepare_lang.sh data/local/dict_nosp "$oov" data/local/lang_tmp_nosp data/lang_nosp
  python3 utils/lang/make_kn_lm.py -ngram-order "$lm_order" -text data/local/lm_small/lm_text.txt \
    -lm data/local/lm_small/lm.arpa
  gzip -f data/local/lm_small/lm.arpa
  utils/format_lm.sh data/lang_nosp data/local/lm_small/lm.arpa.gz data/local/dict_nosp/lexicon.txt $gmm_lang_test
elif [ "$stage" -le 1 ]; then
  "$recipe/local/kaldi/download_lm.sh" "$lm_url" "$lm_dir"
  ln -sfn "$lm_dir" data/local/lm
  local/prepare_dict.sh --stage 3 --nj "$nj" --cmd "$train_cmd" data/local/lm data/local/lm data/local/dict_nosp
  utils/prepare_lang.sh data/local/dict_nosp "<UNK>" data/local/lang_tmp_nosp data/lang_nosp
  local/format_lms.sh --src-dir data/lang_nosp data/local/lm
  utils/build_const_arpa_lm.sh data/local/lm/lm_tglarge.arpa.gz data/lang_nosp data/lang_nosp_test_tglarge
  utils/build_const_arpa_lm.sh data/local/lm/lm_fglarge.arpa.gz data/lang_nosp data/lang_nosp_test_fglarge
fi

if [ "$stage" -le 2 ]; then
  utils/copy_data_dir.sh "$train" data/train
  for i in "${!eval_names[@]}"; do utils/copy_data_dir.sh "${eval_dirs[$i]}" "data/${eval_names[$i]}"; done
  if [ -n "$lm_text" ]; then
    for x in train "${eval_names[@]}"; do
      awk '{ printf "%s", $1; for (i = 2; i <= NF; i++) printf " %s", tolower($i); print "" }' data/$x/text >data/$x/text.tmp
      mv data/$x/text.tmp data/$x/text
    done
  fi
  for x in train "${eval_names[@]}"; do
    steps/make_mfcc.sh --cmd "$train_cmd" --nj "$(jobs_for data/$x "$nj")" data/$x exp/make_mfcc/$x mfcc
    steps/compute_cmvn_stats.sh data/$x exp/make_mfcc/$x mfcc
    utils/fix_data_dir.sh data/$x
  done
fi

if [ "$stage" -le 3 ]; then
  subset data/train 2000 data/train_2kshort --shortest
  subset data/train 5000 data/train_5k
  subset data/train 10000 data/train_10k
  subset data/train 30000 data/train_30k
  steps/train_mono.sh --boost-silence 1.25 --nj "$(jobs_for data/train_2kshort "$nj")" --cmd "$train_cmd" \
    data/train_2kshort data/lang_nosp exp/mono
  steps/align_si.sh --boost-silence 1.25 --nj "$(jobs_for data/train_5k "$nj")" --cmd "$train_cmd" \
    data/train_5k data/lang_nosp exp/mono exp/mono_ali_5k
  steps/train_deltas.sh --boost-silence 1.25 --cmd "$train_cmd" $tri1_size data/train_5k data/lang_nosp \
    exp/mono_ali_5k exp/tri1
  steps/align_si.sh --nj "$(jobs_for data/train_10k "$nj")" --cmd "$train_cmd" data/train_10k data/lang_nosp \
    exp/tri1 exp/tri1_ali_10k
  steps/train_lda_mllt.sh --cmd "$train_cmd" --splice-opts "--left-context=3 --right-context=3" $tri2b_size \
    data/train_10k data/lang_nosp exp/tri1_ali_10k exp/tri2b
fi

if [ "$stop_after" = gmm ]; then
  # Decode each GMM with the small (or tgsmall) LM; score WER and CER. Later stages never run here.
  if [ "$stage" -le 3 ]; then
    for m in mono tri1 tri2b; do
      utils/mkgraph.sh $gmm_lang_test exp/$m exp/$m/graph_$gmm_lm
      for x in "${eval_names[@]}"; do
        dir=exp/$m/decode_${gmm_lm}_$x
        steps/decode.sh --nj "$(jobs_for data/$x "$decode_nj")" --cmd "$decode_cmd" --skip-scoring true \
          exp/$m/graph_$gmm_lm data/$x $dir
        steps/score_kaldi.sh --cmd "$decode_cmd" data/$x exp/$m/graph_$gmm_lm $dir
        steps/scoring/score_kaldi_cer.sh --stage 2 --cmd "$decode_cmd" data/$x exp/$m/graph_$gmm_lm $dir
      done
    done
  fi
  for m in mono tri1 tri2b; do
    for x in "${eval_names[@]}"; do
      dir=exp/$m/decode_${gmm_lm}_$x
      echo "$m $x $(cat $dir/scoring_kaldi/best_wer) | $(cat $dir/scoring_kaldi/best_cer)"
    done
  done | tee exp/gmm_results.txt
  echo "$0: done (--stop-after gmm): $w/exp/gmm_results.txt" >&2
  exit 0
fi

if [ "$stage" -le 3 ]; then
  steps/align_si.sh --nj "$(jobs_for data/train_10k "$nj")" --cmd "$train_cmd" --use-graphs true \
    data/train_10k data/lang_nosp exp/tri2b exp/tri2b_ali_10k
  steps/train_sat.sh --cmd "$train_cmd" 2500 15000 data/train_10k data/lang_nosp exp/tri2b_ali_10k exp/tri3b
  steps/align_fmllr.sh --nj "$(jobs_for data/train_30k "$nj")" --cmd "$train_cmd" data/train_30k data/lang_nosp \
    exp/tri3b exp/tri3b_ali_30k
  steps/train_sat.sh --cmd "$train_cmd" 4200 40000 data/train_30k data/lang_nosp exp/tri3b_ali_30k exp/tri4b
fi

if [ "$stage" -le 4 ]; then
  steps/get_prons.sh --cmd "$train_cmd" data/train_30k data/lang_nosp exp/tri4b
  utils/dict_dir_add_pronprobs.sh --max-normalize true data/local/dict_nosp exp/tri4b/pron_counts_nowb.txt \
    exp/tri4b/sil_counts_nowb.txt exp/tri4b/pron_bigram_counts_nowb.txt data/local/dict
  utils/prepare_lang.sh data/local/dict "<UNK>" data/local/lang_tmp data/lang
  local/format_lms.sh --src-dir data/lang data/local/lm
  utils/build_const_arpa_lm.sh data/local/lm/lm_tglarge.arpa.gz data/lang data/lang_test_tglarge
  utils/build_const_arpa_lm.sh data/local/lm/lm_fglarge.arpa.gz data/lang data/lang_test_fglarge
fi

train_set=train; gmm=tri5b
[ "$cleanup" = true ] && { train_set=train_cleaned; gmm=tri5b_cleaned; }
if [ "$stage" -le 5 ]; then
  steps/align_fmllr.sh --nj "$(jobs_for data/train "$nj")" --cmd "$train_cmd" data/train data/lang exp/tri4b exp/tri4b_ali
  steps/train_sat.sh --cmd "$train_cmd" 5000 100000 data/train data/lang exp/tri4b_ali exp/tri5b
  if [ "$cleanup" = true ]; then
    steps/cleanup/clean_and_segment_data.sh --nj "$(jobs_for data/train "$nj")" --cmd "$train_cmd" \
      --segmentation-opts "--min-segment-length 0.3 --min-new-segment-length 0.6" \
      data/train data/lang exp/tri5b exp/tri5b_cleanup data/train_cleaned
    steps/align_fmllr.sh --nj "$(jobs_for data/train_cleaned "$nj")" --cmd "$train_cmd" data/train_cleaned data/lang \
      exp/tri5b exp/tri5b_ali_cleaned
    steps/train_sat.sh --cmd "$train_cmd" 5000 100000 data/train_cleaned data/lang exp/tri5b_ali_cleaned exp/tri5b_cleaned
  fi
fi

nnet3=exp/nnet3_cleaned
sp=${train_set}_sp
if [ "$stage" -le 6 ]; then
  utils/data/perturb_data_dir_speed_3way.sh data/$train_set data/$sp
  steps/make_mfcc.sh --cmd "$train_cmd" --nj "$(jobs_for data/$sp "$nj")" data/$sp exp/make_mfcc/$sp mfcc_perturbed
  steps/compute_cmvn_stats.sh data/$sp exp/make_mfcc/$sp mfcc_perturbed
  utils/fix_data_dir.sh data/$sp
  steps/align_fmllr.sh --nj "$(jobs_for data/$sp "$nj")" --cmd "$train_cmd" data/$sp data/lang exp/$gmm exp/${gmm}_ali_$sp
  utils/copy_data_dir.sh data/$sp data/${sp}_hires
  utils/data/perturb_data_dir_volume.sh data/${sp}_hires
  for x in ${sp} dev_farfield test_farfield; do
    [ "$x" = "$sp" ] || utils/copy_data_dir.sh data/$x data/${x}_hires
    steps/make_mfcc.sh --cmd "$train_cmd" --nj "$(jobs_for data/${x}_hires "$nj")" --mfcc-config conf/mfcc_hires.conf \
      data/${x}_hires exp/make_hires/$x mfcc_hires
    steps/compute_cmvn_stats.sh data/${x}_hires exp/make_hires/$x mfcc_hires
    utils/fix_data_dir.sh data/${x}_hires
  done
  mkdir -p $nnet3
  subset data/${sp}_hires 10000 data/${sp}_hires_10k
  subset data/${sp}_hires 60000 data/${sp}_hires_60k
  steps/online/nnet2/get_pca_transform.sh --cmd "$train_cmd" --splice-opts "--left-context=3 --right-context=3" \
    --max-utts 10000 --subsample 2 data/${sp}_hires_10k $nnet3/pca_transform
  steps/online/nnet2/train_diag_ubm.sh --cmd "$train_cmd" --nj "$(jobs_for data/${sp}_hires_10k "$nj")" \
    --num-frames 700000 data/${sp}_hires_10k 512 $nnet3/pca_transform $nnet3/diag_ubm
  steps/online/nnet2/train_ivector_extractor.sh --cmd "$train_cmd" --nj "$(jobs_for data/${sp}_hires_60k 10)" \
    data/${sp}_hires_60k $nnet3/diag_ubm $nnet3/extractor
  utils/data/modify_speaker_info.sh --utts-per-spk-max 2 data/${sp}_hires data/${sp}_hires_max2
  steps/online/nnet2/extract_ivectors_online.sh --cmd "$train_cmd" --nj "$(jobs_for data/${sp}_hires_max2 "$nj")" \
    data/${sp}_hires_max2 $nnet3/extractor $nnet3/ivectors_${sp}_hires
  for x in dev_farfield test_farfield; do
    steps/online/nnet2/extract_ivectors_online.sh --cmd "$train_cmd" --nj "$(jobs_for data/${x}_hires "$nj")" \
      data/${x}_hires $nnet3/extractor $nnet3/ivectors_${x}_hires
  done
fi

lang=data/lang_chain
ali_dir=exp/${gmm}_ali_$sp
lat_dir=exp/chain_cleaned/${gmm}_${sp}_lats
tree_dir=exp/chain_cleaned/tree_sp
dir=exp/chain_cleaned/tdnn_1d_sp
if [ "$stage" -le 7 ]; then
  rm -rf $lang
  cp -r data/lang $lang
  silphonelist=$(cat $lang/phones/silence.csl)
  nonsilphonelist=$(cat $lang/phones/nonsilence.csl)
  steps/nnet3/chain/gen_topo.py "$nonsilphonelist" "$silphonelist" >$lang/topo
  steps/align_fmllr_lats.sh --nj "$(jobs_for data/$sp "$nj")" --cmd "$train_cmd" data/$sp data/lang exp/$gmm $lat_dir
  rm -f $lat_dir/fsts.*.gz
  steps/nnet3/chain/build_tree.sh --frame-subsampling-factor 3 --context-opts "--context-width=2 --central-position=1" \
    --cmd "$train_cmd" 7000 data/$sp $lang $ali_dir $tree_dir
  xent_regularize=0.1
  num_targets=$(tree-info $tree_dir/tree | grep num-pdfs | awk '{print $2}')
  learning_rate_factor=$(awk -v x=$xent_regularize 'BEGIN {print 0.5 / x}')
  affine_opts="l2-regularize=0.008 dropout-proportion=0.0 dropout-per-dim=true dropout-per-dim-continuous=true"
  tdnnf_opts="l2-regularize=0.008 dropout-proportion=0.0 bypass-scale=0.75"
  linear_opts="l2-regularize=0.008 orthonormal-constraint=-1.0"
  prefinal_opts="l2-regularize=0.008"
  output_opts="l2-regularize=0.002"
  mkdir -p $dir/configs
  {
    echo "input dim=100 name=ivector"
    echo "input dim=40 name=input"
    echo "fixed-affine-layer name=lda input=Append(-1,0,1,ReplaceIndex(ivector, t, 0)) affine-transform-file=$dir/configs/lda.mat"
    echo "relu-batchnorm-dropout-layer name=tdnn1 $affine_opts dim=1536"
    for i in $(seq 2 17); do
      case $i in 2|3|4) s=1 ;; 5) s=0 ;; *) s=3 ;; esac
      echo "tdnnf-layer name=tdnnf$i $tdnnf_opts dim=1536 bottleneck-dim=160 time-stride=$s"
    done
    echo "linear-component name=prefinal-l dim=256 $linear_opts"
    echo "prefinal-layer name=prefinal-chain input=prefinal-l $prefinal_opts big-dim=1536 small-dim=256"
    echo "output-layer name=output include-log-softmax=false dim=$num_targets $output_opts"
    echo "prefinal-layer name=prefinal-xent input=prefinal-l $prefinal_opts big-dim=1536 small-dim=256"
    echo "output-layer name=output-xent dim=$num_targets learning-rate-factor=$learning_rate_factor $output_opts"
  } >$dir/configs/network.xconfig
  steps/nnet3/xconfig_to_configs.py --xconfig-file $dir/configs/network.xconfig --config-dir $dir/configs/
  steps/nnet3/chain/train.py --stage -10 --cmd "$decode_cmd" --use-gpu "$use_gpu" \
    --feat.online-ivector-dir $nnet3/ivectors_${sp}_hires \
    --feat.cmvn-opts "--norm-means=false --norm-vars=false" \
    --chain.xent-regularize $xent_regularize --chain.leaky-hmm-coefficient 0.1 --chain.l2-regularize 0.0 \
    --chain.apply-deriv-weights false --chain.lm-opts="--num-extra-lm-states=2000" \
    --egs.stage -10 --egs.opts "--frames-overlap-per-eg 0 --constrained false" --egs.chunk-width 150,110,100 \
    --trainer.dropout-schedule '0,0@0.20,0.5@0.50,0' \
    --trainer.add-option="--optimization.memory-compression-level=2" \
    --trainer.num-chunk-per-minibatch 64 --trainer.frames-per-iter 2500000 --trainer.num-epochs 4 \
    --trainer.optimization.num-jobs-initial "$num_jobs_initial" --trainer.optimization.num-jobs-final "$num_jobs_final" \
    --trainer.optimization.initial-effective-lrate 0.00015 --trainer.optimization.final-effective-lrate 0.000015 \
    --trainer.max-param-change 2.0 --cleanup.remove-egs true \
    --feat-dir data/${sp}_hires --tree-dir $tree_dir --lat-dir $lat_dir --dir $dir
fi

if [ "$stage" -le 8 ]; then
  graph=$dir/graph_tgsmall
  utils/mkgraph.sh --self-loop-scale 1.0 --remove-oov data/lang_test_tgsmall $dir $graph
  steps/online/nnet3/prepare_online_decoding.sh --mfcc-config conf/mfcc_hires.conf $lang $nnet3/extractor $dir ${dir}_online
  for x in test_farfield dev_farfield; do
    steps/nnet3/decode.sh --acwt 1.0 --post-decode-acwt 10.0 --nj "$(jobs_for data/${x}_hires "$decode_nj")" \
      --cmd "$decode_cmd" --online-ivector-dir $nnet3/ivectors_${x}_hires $graph data/${x}_hires $dir/decode_${x}_tgsmall
    steps/lmrescore.sh --cmd "$decode_cmd" --self-loop-scale 1.0 data/lang_test_{tgsmall,tgmed} \
      data/${x}_hires $dir/decode_${x}_{tgsmall,tgmed}
    steps/lmrescore_const_arpa.sh --cmd "$decode_cmd" data/lang_test_{tgsmall,tglarge} \
      data/${x}_hires $dir/decode_${x}_{tgsmall,tglarge}
    steps/lmrescore_const_arpa.sh --cmd "$decode_cmd" data/lang_test_{tgsmall,fglarge} \
      data/${x}_hires $dir/decode_${x}_{tgsmall,fglarge}
    # Online decoding: one job per speaker, i-vectors estimated as the audio arrives.
    steps/online/nnet3/decode.sh --acwt 1.0 --post-decode-acwt 10.0 --nj "$(wc -l <data/$x/spk2utt)" \
      --cmd "$decode_cmd" $graph data/$x ${dir}_online/decode_${x}_tgsmall
  done
fi
echo "$0: done: $w/$dir" >&2
