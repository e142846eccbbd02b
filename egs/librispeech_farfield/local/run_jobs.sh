#!/usr/bin/env bash
# A local job runner with the contract of Kaldi's utils/run.pl, for machines without Kaldi
# (cmd.sh picks Kaldi's run.pl / queue.pl / slurm.pl when Kaldi is present):
#
#   run_jobs.sh [options] [JOB=1:N] <log-file> <command> [<arg>...]
#
# * JOB=a:b runs the command once per index; every occurrence of the name (any identifier, here
#   JOB) in the log name and the command is replaced by the index, as run.pl does.
# * The words of the command are joined into one bash command line with run.pl's quoting (a word
#   with spaces is quoted), so an escaped pipe (\|) in the caller's command is a pipe here.
# * Each job's stdout and stderr go to its log, between run.pl's header ("# <command>",
#   "# Started at ...") and footer ("# Accounting: time=... threads=...", "# Ended (code N) at ...").
# * --max-jobs-run N (or -tc N) bounds concurrency (default: the number of CPUs); --num-threads N is
#   reported in the footer; other run.pl/queue.pl options with a value (--mem 2G, --gpu 0, ...) are
#   accepted and ignored, as run.pl ignores them.
# * Exit status 1 if any job failed, with the failed count and the log name on stderr.
set -u

usage() {
  echo "Usage: $0 [--max-jobs-run N] [--mem X] [--num-threads N] [JOB=1:N] <log-file> <command> [<arg>...]" >&2
  echo "e.g.: $0 JOB=1:4 exp/log/simulate.JOB.log rir-simulate rooms.JOB.txt out/JOB" >&2
  exit 1
}

# All cores, as run.pl counts them: GNU nproc alone honours OMP_NUM_THREADS, which cluster set-ups
# often export as 1 (and then ran one job at a time).
max_jobs=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc 2>/dev/null || echo 1)
num_threads=1
jobname=""
jobstart=1
jobend=1

for pass in 1 2; do  # run.pl allows JOB=1:N between the options
  while [ $# -ge 2 ] && [ "${1#-}" != "$1" ]; do
    switch=$1
    shift
    case "$switch" in
      -V) ;;
      --max-jobs-run|-tc) max_jobs=$1; shift ;;
      --num-threads) num_threads=$1; shift ;;
      *) shift ;;  # --mem, --gpu, -l, ...: meaningful to queue.pl/slurm.pl only
    esac
  done
  if [ $# -ge 1 ]; then
    if [[ "$1" =~ ^([A-Za-z_][A-Za-z0-9_]*)=([0-9]+):([0-9]+)$ ]]; then
      jobname=${BASH_REMATCH[1]}; jobstart=${BASH_REMATCH[2]}; jobend=${BASH_REMATCH[3]}; shift
    elif [[ "$1" =~ ^([A-Za-z_][A-Za-z0-9_]*)=([0-9]+)$ ]]; then
      jobname=${BASH_REMATCH[1]}; jobstart=${BASH_REMATCH[2]}; jobend=${BASH_REMATCH[2]}; shift
    fi
  fi
  [ "$pass" = 1 ] || break
done
[ $# -ge 2 ] || usage
if ! [[ "$max_jobs" =~ ^[0-9]+$ ]] || [ "$max_jobs" -lt 1 ]; then
  echo "$0: --max-jobs-run must be a positive integer, got '$max_jobs'" >&2
  exit 1
fi
if [ "$jobstart" -gt "$jobend" ]; then
  echo "$0: empty job range $jobname=$jobstart:$jobend" >&2
  exit 1
fi
if [ -n "$jobname" ] && [ "$jobend" -gt "$jobstart" ] && [[ "$1" != *"$jobname"* ]]; then
  echo "$0: the log file $1 does not contain $jobname: the jobs would overwrite one log" >&2
  exit 1
fi

logfile=$1
shift
cmd=""
for word in "$@"; do
  if [[ "$word" =~ ^[^[:space:]]+$ ]]; then cmd+="$word "
  elif [[ "$word" != *\"* ]]; then cmd+="\"$word\" "
  else cmd+="'$word' "
  fi
done

run_one() {
  local id=$1 c=$cmd l=$logfile start end rc
  if [ -n "$jobname" ]; then
    c=${c//$jobname/$id}
    l=${l//$jobname/$id}
  fi
  mkdir -p "$(dirname "$l")" || return 1
  {
    echo "# $c"
    echo "# Started at $(date)"
    echo "#"
  } >"$l" || return 1
  start=$(date +%s)
  bash -c "( $c ) 2>>'$l' >>'$l'" </dev/null
  rc=$?
  end=$(date +%s)
  {
    echo "# Accounting: time=$((end - start)) threads=$num_threads"
    echo "# Ended (code $rc) at $(date)"
  } >>"$l"
  return $rc
}

failed=0
total=$((jobend - jobstart + 1))
running=0
for ((id = jobstart; id <= jobend; id++)); do
  if [ "$running" -ge "$max_jobs" ]; then
    wait -n || failed=$((failed + 1))
    running=$((running - 1))
  fi
  run_one "$id" &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=$((failed + 1))
  running=$((running - 1))
done

if [ "$failed" -gt 0 ]; then
  if [ "$total" -eq 1 ]; then
    echo "$0: job failed, log is in ${logfile//$jobname/$jobstart}" >&2
  else
    echo "$0: $failed / $total failed, log is in $logfile" >&2
  fi
  exit 1
fi
exit 0
