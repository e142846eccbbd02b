#!/usr/bin/env bash
# The recipe's parallel stages through Kaldi's slurm.pl on a real Slurm: `run.sh --demo --demo-size
# tiny` (stages 0-7) with TSRIR_CMD=slurm.pl. Checks that it finishes, that the jobs of the parallel
# stages ran as Slurm jobs (their logs carry SLURM_JOB_ID and slurm.pl's batch files), and that a
# program run with --num-threads N got N CPUs from Slurm (SLURM_CPUS_PER_TASK=N): the slots were
# asked for. Runs when a Slurm partition answers (`sinfo`) and KALDI_ROOT has utils/slurm.pl;
# skipped (77) otherwise. Set-up used for bench/RESULTS.md: Debian's slurm-wlm 22.05 + munge on the
# dev VM, one node (2 CPUs), partition "shared" (the one slurm.pl's default config asks for).
# Env: TSRIR_BIN (set by CTest), KALDI_ROOT.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
recipe=$(cd "$here/../../egs/librispeech_farfield" && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
[ -n "${KALDI_ROOT:-}" ] && [ -x "$KALDI_ROOT/egs/wsj/s5/utils/slurm.pl" ] ||
  { echo "SKIP: KALDI_ROOT with utils/slurm.pl is needed"; exit 77; }
command -v sinfo >/dev/null && command -v sbatch >/dev/null || { echo "SKIP: no Slurm client (sinfo, sbatch)"; exit 77; }
state=$(timeout 10 sinfo -h -o %a 2>/dev/null | head -n 1)
[ "$state" = up ] || { echo "SKIP: no Slurm partition is up (sinfo: '${state:-no answer}')"; exit 77; }
for p in ts-rirgan-train gas-to-real; do
  [ -x "$TSRIR_BIN/$p" ] || { echo "SKIP: $p not built; the demo needs it"; exit 77; }
done
export PATH=$TSRIR_BIN:$PATH LC_ALL=C TSRIR_CMD=slurm.pl
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tsrir_slurm.XXXXXX")   # on a cluster: a directory every node sees
trap 'rm -rf "$tmp"' EXIT
w=$tmp/demo
failures=0
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else echo "FAIL: $what" >&2; failures=$((failures + 1)); fi; }

start=$SECONDS
"$recipe/run.sh" --demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md" >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then tail -n 30 "$tmp/err" >&2; echo "FAIL: run.sh with TSRIR_CMD=slurm.pl exited with $rc" >&2; exit 1; fi
echo "ok: run.sh --demo --demo-size tiny through slurm.pl in $((SECONDS - start)) s"
for s in 2 3 4 5 7; do check "stage $s done" grep -q "^run.sh: stage $s done" "$tmp/err"; done
logs=$(grep -rl '^# Running on' "$w" 2>/dev/null | sort)
n=$(grep -l 'SLURM_JOB_ID' $logs 2>/dev/null | wc -l)
echo "job logs: $(echo "$logs" | grep -c .), of which Slurm jobs: $n"
check "the parallel stages ran as Slurm jobs" [ "$n" -ge 4 ]
check "slurm.pl's batch files exist (sbatch was used)" bash -c "find '$w' -path '*/q/*.sh' | grep -q ."
threaded=$(grep -l 'SLURM_CPUS_PER_TASK=2' $logs 2>/dev/null | wc -l)
echo "jobs that got 2 CPUs (--num-threads 2): $threaded"
check "--num-threads reached Slurm (SLURM_CPUS_PER_TASK=2)" [ "$threaded" -ge 1 ]
for l in $logs; do echo "  $(basename "$l"): $(grep -o 'SLURM_JOB_ID=[0-9]*' "$l" | head -n 1) $(grep -o 'SLURM_CPUS_PER_TASK=[0-9]*' "$l" | head -n 1)"; done
[ $failures -eq 0 ] && echo "PASS: the recipe's parallel stages through slurm.pl" || echo "FAIL: $failures checks"
exit $((failures > 0))
