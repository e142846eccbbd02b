#!/usr/bin/env bash
# Collects the WERs of stage 8 into the paper's Table 2 layout (a Markdown table on stdout):
#   | Training data | fglarge | tglarge | tgmed | tgsmall | online |
# one row per training set, in the paper's order: clean (Baseline), real (Oracle), GAS, GAS+EQ,
# G(GAS+EQ), G(GAS), G(GAS)+EQ. For set S the decodes are read from Kaldi's layout under
# <kaldi-root>/S (local/kaldi/run_asr.sh): exp/chain*/tdnn*_sp/decode_<test-set>_<lm>/wer_* and
# exp/chain*/tdnn*_sp_online/decode_<test-set>_tgsmall/wer_*. Each cell is the best (lowest) WER
# over the wer_<lmwt>_<penalty> files of the decode, as Kaldi's utils/best_wer.sh picks it;
# a decode that is missing is shown as "-" and counted in a note under the table.
# Exit status 1 if no WER at all was found.
set -euo pipefail
sets="clean real gas gas_eq gas_eq_gsr gas_gsr gas_gsr_eq"
test_set=test_farfield
help_message="Usage: $0 [--sets 'clean real gas ...'] [--test-set name] <kaldi-root>
e.g.: $0 --test-set test_farfield exp/kaldi"
. "$(dirname "$0")/parse_options.sh"
[ $# -eq 1 ] || { echo "$help_message" >&2; exit 1; }
root=$1
[ -d "$root" ] || { echo "$0: no such directory $root" >&2; exit 1; }

label() {
  case $1 in
    clean) echo "clean (Baseline)" ;; real) echo "real (Oracle)" ;; gas) echo "GAS" ;;
    gas_eq) echo "GAS+EQ" ;; gas_eq_gsr) echo "G(GAS+EQ)" ;; gas_gsr) echo "G(GAS)" ;;
    gas_gsr_eq) echo "G(GAS)+EQ" ;; gas_ext) echo "GAS-ext" ;; *) echo "$1" ;;
  esac
}
# The best %WER of a decode directory, or "-" when it has no wer_* file.
best_wer() {
  local d=$1
  if [ -d "$d" ] && ls "$d"/wer_* >/dev/null 2>&1; then
    grep -h '%WER' "$d"/wer_* | awk 'BEGIN {best = ""}
      {v = $2 + 0; if (best == "" || v < best) best = v}
      END {if (best == "") print "-"; else printf "%.2f\n", best}'
  else
    echo "-"
  fi
}
# The first directory (sorted) matching a glob, or the pattern itself when nothing matches.
first_match() { local m; m=$(compgen -G "$1" | LC_ALL=C sort | head -n 1 || true); echo "${m:-$1}"; }

# Paper order, then any other requested set.
ordered=""
for s in clean real gas gas_eq gas_eq_gsr gas_gsr gas_gsr_eq; do [[ " $sets " == *" $s "* ]] && ordered+="$s "; done
for s in $sets; do [[ " $ordered " == *" $s "* ]] || ordered+="$s "; done

echo "| Training data | fglarge | tglarge | tgmed | tgsmall | online |"
echo "|---|---|---|---|---|---|"
found=0; missing=0
for s in $ordered; do
  row="| $(label "$s")"
  chain=$(first_match "$root/$s/exp/chain*/tdnn*_sp")
  for lm in fglarge tglarge tgmed tgsmall; do
    w=$(best_wer "$chain/decode_${test_set}_$lm")
    if [ "$w" = - ]; then missing=$((missing + 1)); else found=$((found + 1)); fi
    row+=" | $w"
  done
  w=$(best_wer "$(first_match "$root/$s/exp/chain*/tdnn*_sp_online")/decode_${test_set}_tgsmall")
  if [ "$w" = - ]; then missing=$((missing + 1)); else found=$((found + 1)); fi
  echo "$row | $w |"
done
[ "$missing" -eq 0 ] || { echo; echo "($missing decode(s) missing, shown as -.)"; }
[ "$found" -gt 0 ] || { echo "$0: no WER found under $root for test set $test_set" >&2; exit 1; }
exit 0
