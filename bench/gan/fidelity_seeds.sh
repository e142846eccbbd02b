#!/usr/bin/env bash
# TS-RIRGAN translation-fidelity suite over several seeds and hidden-effect kinds (issues 17, 34):
# for each kind and seed, new data (tests/gan/fidelity_domains.cc), a model trained with the given
# ts-rirgan-train options, held-out synthetic RIRs translated, and every measure printed
# (tests/gan/fidelity_measures.h), then the pass count per kind. One LibTorch thread per run;
# JOBS runs in parallel (default 2). DEADLINE_S bounds the whole script's runs (a GPU lease): a run
# still going then is stopped and reads as failed ("stopped at the deadline"), later ones are not
# started; both are counted as not passed.
# Usage: bench/gan/fidelity_seeds.sh [build-dir] [seeds, e.g. "1 2 3 4 5"] ["ts-rirgan-train options"] [kinds]
# Default options: the program's defaults at the width and batch issue 17 names and the 2000 steps they are judged at; default
# kinds: all four (low-frequency decay direct early).
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build}
seeds=${2:-1 2 3 4 5}
args=${3:---width=16 --batch-size=4 --steps=2000}
kinds=${4:-low-frequency decay direct early}
suite=$build/bin/gan-fidelity-suite
[[ -x $suite ]] || { echo "missing $suite (ninja -C $build gan-fidelity-suite)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $(getconf _NPROCESSORS_ONLN) cores, load: $(cut -d' ' -f1-3 /proc/loadavg); options: $args"
run_one() {  # kind seed
  local start end limit=() left
  if [[ -n $t_end ]]; then
    left=$((t_end - $(date +%s)))
    if ((left < 20)); then echo "kind $1 seed $2: not run (DEADLINE_S spent)" > "$work/$1.$2.out"; return 0; fi
    limit=(timeout -s TERM "$left")
  fi
  start=$(cut -d' ' -f1 /proc/loadavg)
  # CPU time by /usr/bin/time where there is one (GPU images may lack it).
  local timer=()
  [[ -x /usr/bin/time ]] && timer=(/usr/bin/time -f "%U %S" -o "$work/$1.$2.time")
  ${timer[@]+"${timer[@]}"} ${limit[@]+"${limit[@]}"} \
    "$suite" --effect="$1" "$build/bin" "$work/$1.seed$2" "$2" "$args" 1 > "$work/$1.$2.out" 2>&1 ||
    { [[ $? == 124 ]] && echo "kind $1 seed $2: stopped at the deadline" >> "$work/$1.$2.out"; true; }
  end=$(cut -d' ' -f1 /proc/loadavg)
  echo "  (load $start at start, $end at end; CPU s $(awk 'END {print $1 + $2}' "$work/$1.$2.time" 2>/dev/null || echo n/a))" >> "$work/$1.$2.out"
}
t_end=""
[[ -n ${DEADLINE_S:-} ]] && t_end=$(($(date +%s) + DEADLINE_S))
export -f run_one
export args suite build work t_end
for k in $kinds; do for s in $seeds; do echo "$k $s"; done; done | xargs -P "${JOBS:-2}" -L1 bash -c 'run_one "$0" "$1"'
for k in $kinds; do
  passed=0
  echo "## kind $k"
  for s in $seeds; do
    cat "$work/$k.$s.out"
    grep -q '; PASS$' "$work/$k.$s.out" && passed=$((passed + 1))
  done
  echo "kind $k: passed $passed of $(echo $seeds | wc -w) seeds"
done
echo "# done $(date -u +%Y-%m-%dT%H:%MZ), load: $(cut -d' ' -f1-3 /proc/loadavg)"
