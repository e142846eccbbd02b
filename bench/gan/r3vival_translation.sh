#!/usr/bin/env bash
# TS-RIRGAN on real data (issue 17, part 3): R3VIVAL's measured RIRs are the real domain, GAS of
# the same set-ups (rir-simulate, the stated set-up of docs/results/make_r3vival_inputs.sh, the
# direct sound aligned to 10 ms as R3VIVAL's) the synthetic one. Train and test are split by
# SOURCE POSITION (positions sorted, alternating), so no test set-up was seen in training. Trains
# with the program's defaults, translates the test GAS, measures GAS, G(GAS) and the real test RIRs
# with rir-metrics, and writes docs/results/ts-rirgan-r3vival.md (Table 1 means and the per-RIR
# input->output correlations).
# Usage: bench/gan/r3vival_translation.sh [build-dir] [out-page] ["ts-rirgan-train options"]
# R3VIVAL_KEEP=DIR keeps the work (model, GAS and translated test RIRs, metrics) in DIR, a new
# directory, which is then the work directory (its lists name the files there).
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build}
page=${2:-$here/docs/results/ts-rirgan-r3vival.md}
train_args=${3:---width=16 --batch-size=4 --steps=1000 --seed=1 --num-threads=2}
r3=${R3VIVAL_DIR:-$here/../shared/data/rirs/r3vival}
[[ -d $r3 ]] || { echo "$0: R3VIVAL absent ($r3); nothing measured" >&2; exit 2; }
bin=$build/bin
keep=${R3VIVAL_KEEP:-}
[[ -z $keep || ! -e $keep ]] || { echo "$0: R3VIVAL_KEEP=$keep exists; give a new directory" >&2; exit 1; }
if [[ -n $keep ]]; then
  mkdir -p "$keep"
  work=$(cd "$keep" && pwd)
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
load0=$(cut -d' ' -f1-3 /proc/loadavg)
date0=$(date -u +%Y-%m-%dT%H:%MZ)
"$here/docs/results/make_r3vival_inputs.sh" "$r3" "$work/in"
"$bin/rir-simulate" --model=gas+onset_shift:align_ms=10 --sample-rate=16000 --format=float \
  --num-threads=2 "$work/in/rooms.txt" "$work/gas" 2> "$work/simulate.log"
# Source positions: the S<azimuth>-<distance> (or BG<n>) part of the id.
position() { sed -E 's/^RLRVarAcLab_Absorptive_[0-9]+_(S[^_]+)_.*/\1/'; }
cut -d' ' -f1 "$work/in/rir.scp" | position | sort -u | awk 'NR % 2 == 1' > "$work/train_positions"
split_scp() {  # scp, train-out, test-out
  while read -r id path; do
    if grep -qx "$(echo "$id" | position)" "$work/train_positions"; then echo "$id $path" >> "$2"
    else echo "$id $path" >> "$3"; fi
  done < "$1"
}
split_scp "$work/in/rir.scp" "$work/real_train.scp" "$work/real_test.scp"
split_scp "$work/gas/rir.scp" "$work/gas_train.scp" "$work/gas_test.scp"
echo "# train: $(wc -l < "$work/real_train.scp") real + $(wc -l < "$work/gas_train.scp") GAS RIRs ($(wc -l < "$work/train_positions") positions); test: $(wc -l < "$work/real_test.scp") + $(wc -l < "$work/gas_test.scp")" >&2
t0=$(date +%s)
# shellcheck disable=SC2086
"$bin/ts-rirgan-train" $train_args --real="$work/real_train.scp" --synthetic="$work/gas_train.scp" "$work/model" \
  2> "$work/train.log" || { tail -5 "$work/train.log" >&2; exit 1; }
train_s=$(( $(date +%s) - t0 ))
"$bin/gas-to-real" --model="$work/model" --num-threads=2 "$work/gas_test.scp" "$work/g_gas" 2> "$work/translate.log"
for set in real_test gas_test; do "$bin/rir-metrics" --format=json "$work/$set.scp" > "$work/$set.json"; done
"$bin/rir-metrics" --format=json "$work/g_gas/rir.scp" > "$work/g_gas.json"
cmd="bench/gan/r3vival_translation.sh ${1:-build}${2:+ $2}${3:+ \"$3\"}"
python3 "$here/bench/gan/r3vival_table.py" "$work/real_test.json" "$work/gas_test.json" "$work/g_gas.json" \
  --command "$cmd" --train-args "$train_args" --train-s "$train_s" \
  --generator "$(awk '$1 == "generator" {print $2}' "$work/model/settings.txt")" \
  --machine "$(uname -n), $(getconf _NPROCESSORS_ONLN) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" \
  --date "$date0" --load "$load0 at start, $(cut -d' ' -f1-3 /proc/loadavg) at end" \
  --split "$(wc -l < "$work/train_positions") of $(cut -d' ' -f1 "$work/in/rir.scp" | position | sort -u | wc -l) source positions for training ($(wc -l < "$work/real_train.scp") real + $(wc -l < "$work/gas_train.scp") GAS RIRs), the other positions for test ($(wc -l < "$work/real_test.scp") + $(wc -l < "$work/gas_test.scp"))" \
  > "$page.tmp"
mv "$page.tmp" "$page"
cp "$work/model/loss_curves.svg" "$(dirname "$page")/ts-rirgan-r3vival-loss.svg"
echo "wrote $page (training $train_s s)" >&2
