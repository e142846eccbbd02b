#!/usr/bin/env bash
# The downstream experiment's premise in small (issue 19): a recogniser trained on reverberant
# speech beats one trained on clean speech when both decode reverberant speech. Without it, Table 2
# (stage 8 --asr proxy) could not tell RIR sets apart.
#   speech  spoken digit strings from espeak-ng (make_digit_corpus.sh), train and test strings apart
#   RIRs    measured: R3VIVAL (../shared/data/rirs/r3vival, condition 000, T30 ~0.75 s), the
#           positions split into training and held-out test RIRs; when ../shared/data is absent
#           (a clone outside this workplace), RIRs from the independent generator of tests/diagnose
#           (make_test_rirs: no code of the simulator under study). Either way, not our simulator.
#   models  asr-train on clean and on reverberant training speech, seeds 1 and 2, decoded on the
#           test strings convolved with the held-out RIRs (reverberate-data, no noise)
# Passes when, for EACH seed, the reverberant model's CER is at least MARGIN_PCT % (relative)
# below the clean model's, AND a two-sided exact sign test over test utterances (character
# errors summed over seeds; ties dropped) gives p < 0.01. Both statistics are computed here, apart
# from the recipe's table2.sh. The margin is issue 19's (>= 25 % at p < 0.01); what the test
# costs, its margin over six seeds (48-73 %) and the CONTROL run (fails, as it must) are in
# docs/results/downstream.md, "The sensitivity test in CI".
# Env: TSRIR_BIN (built programs), TSRIR_TEST_RIRS (make_test_rirs), ASR_SENSITIVITY_CONTROL=1 to
# train the "reverberant" arm on clean speech too (seeds 3 and 4): the test must then FAIL.
# Exit 77: espeak-ng missing.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$here/asr_test_lib.sh"
require_programs asr-train asr-decode reverberate-data
MARGIN_PCT=${MARGIN_PCT:-25}
N_TRAIN=${N_TRAIN:-160}
N_TEST=${N_TEST:-48}
TRAIN_OPTS=${TRAIN_OPTS:-"--epochs=12 --conv-layers=1 --conv-channels=48 --rnn-layers=1 --rnn-hidden=48 --batch-size=8 --learning-rate=4e-3"}
control=${ASR_SENSITIVITY_CONTROL:-0}
read -r seed1 seed2 <<<"${ASR_SENSITIVITY_SEEDS:-1 2}"   # other seeds: for measuring the margin
shared=${TSRIR_SHARED_DATA:-$repo/../shared/data}
start=$SECONDS

"$here/make_digit_corpus.sh" "$tmp/c" 7 "$N_TRAIN" "$N_TEST" || { echo "FAIL: make_digit_corpus.sh" >&2; exit 1; }

split_test_rirs 000 "$shared"

reverb "$tmp/train_rir_list" "$tmp/c/train" "$tmp/c/train_rvb"
reverb "$tmp/test_rir_list" "$tmp/c/test" "$tmp/c/test_rvb"

# Two arms x two seeds, two trainings at a time (one thread each).
seeds_a="$seed1 $seed2"
if [ "$control" = 1 ]; then arm_b=$tmp/c/train; seeds_b="$((seed1 + 100)) $((seed2 + 100))"; echo "CONTROL: both arms trained on clean speech"
else arm_b=$tmp/c/train_rvb; seeds_b=$seeds_a; fi
train() {  # <data> <model> <seed>
  # shellcheck disable=SC2086
  asr-train $TRAIN_OPTS --num-threads=1 --seed="$3" --progress-interval=600 "$1" "$2" 2>"$2.log" &&
    asr-decode "$2" "$tmp/c/test_rvb" "$2/decode" 2>>"$2.log" || { tail "$2.log" >&2; return 1; }
}
# shellcheck disable=SC2034  # read through ${!sb} below
read -r b1 b2 <<<"$seeds_b"
for k in 1 2; do
  sa=seed$k; sb=b$k; sa=${!sa}; sb=${!sb}
  train "$tmp/c/train" "$tmp/clean_$k" "$sa" & p1=$!
  train "$arm_b" "$tmp/rvb_$k" "$sb" & p2=$!
  wait $p1 || { echo "FAIL: training the clean model, seed $sa" >&2; exit 1; }
  wait $p2 || { echo "FAIL: training the reverberant model, seed $sb" >&2; exit 1; }
done

failures=0
rate() { awk '/^%WER/ { print $2 }' "$1"; }
for k in 1 2; do
  c=$(rate "$tmp/clean_$k/decode/cer") r=$(rate "$tmp/rvb_$k/decode/cer")
  rel=$(awk -v c="$c" -v r="$r" 'BEGIN { printf "%.1f", 100 * (c - r) / c }')
  if awk -v x="$rel" -v m="$MARGIN_PCT" 'BEGIN { exit !(x >= m) }'; then
    echo "ok: run $k: reverberant-trained CER $r % vs clean-trained $c %: $rel % relative reduction (>= $MARGIN_PCT %)"
  else
    echo "FAIL: run $k: reverberant-trained CER $r % vs clean-trained $c %: $rel % relative reduction (< $MARGIN_PCT %)" >&2
    failures=$((failures + 1))
  fi
done
# Exact two-sided sign test: per test utterance, the character errors of both seeds summed per arm.
p=$(awk '!/^#/ { e[FILENAME ~ /clean_/ ? "c" : "r", $1] += $8; u[$1] = 1 }
  END { for (i in u) { d = e["c", i] - e["r", i]; if (d > 0) np++; else if (d < 0) nm++ }
        n = np + nm; k = (np > nm ? np : nm); q = 0; b = 1
        for (j = 0; j <= n; j++) { if (j > 0) b = b * (n - j + 1) / j; if (j >= k) q += b }
        q = 2 * q / 2 ^ n; if (q > 1) q = 1
        printf "%.3g %d %d\n", q, np, nm }' "$tmp"/clean_?/decode/utt_errors "$tmp"/rvb_?/decode/utt_errors)
read -r pv np nm <<<"$p"
if awk -v p="$pv" -v a="$np" -v b="$nm" 'BEGIN { exit !(p < 0.01 && a > b) }'; then
  echo "ok: sign test over test utterances: $np better with reverberant training, $nm worse, p = $pv (< 0.01)"
else
  echo "FAIL: sign test over test utterances: $np better with reverberant training, $nm worse, p = $pv (needs more better than worse at p < 0.01)" >&2
  failures=$((failures + 1))
fi
echo "($((SECONDS - start)) s)"
[ $failures -eq 0 ] || { echo "$failures check(s) failed" >&2; exit 1; }
echo "the reverberant-trained recogniser beats the clean-trained one on reverberant speech"
