# How parallel jobs run: `$train_cmd JOB=1:$nj <log> <command>` (Kaldi's convention).
# With Kaldi (KALDI_ROOT set): Kaldi's run.pl on this machine; on a cluster set TSRIR_CMD to
# queue.pl (SGE, conf/queue.conf) or slurm.pl before running, or edit the lines below, as in any
# Kaldi recipe. Without Kaldi: local/run_jobs.sh, a runner with run.pl's JOB=1:N contract.
if [ -n "${KALDI_ROOT:-}" ] && [ -f "$KALDI_ROOT/egs/wsj/s5/utils/run.pl" ]; then
  tsrir_cmd=${TSRIR_CMD:-run.pl}
else
  tsrir_cmd=${TSRIR_CMD:-run_jobs.sh}
fi
export train_cmd="$tsrir_cmd --mem 2G"
export decode_cmd="$tsrir_cmd --mem 4G"
export mkgraph_cmd="$tsrir_cmd --mem 8G"
# TS-RIRGAN training; add --gpu 1 for queue.pl/slurm.pl when training with --gan-device cuda.
export gan_cmd="$tsrir_cmd --mem 4G"
