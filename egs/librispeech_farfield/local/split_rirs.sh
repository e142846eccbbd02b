#!/usr/bin/env bash
# Splits a real-RIR metadata table (<rir-id> <room-id> ...) into train/dev/test, the paper's
# 773/194/242 split of BUT ReverbDB (TS-RIR sec. 4.2: "We randomly split 1209 RIRs ... into subsets
# of {773,194,242}"). The split is a seeded random permutation that depends only on (seed, rir id):
# RIRs are ordered by md5("<seed> <rir-id>") and cut in that order, so it is reproducible on any
# machine and independent of the table's order. When the table does not hold exactly the sum of
# --sizes RIRs, the sizes are scaled to its count (dev and test rounded, train = the rest).
# Writes <out-dir>/{train,dev,test}.ids (sorted) and <out-dir>/split.txt (the sizes used).
set -euo pipefail
seed=0
sizes=773:194:242
help_message="Usage: $0 [--seed N] [--sizes train:dev:test] <meta.txt> <out-dir>"
. ./local/parse_options.sh
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
meta=$1; out=$2
[ -s "$meta" ] || { echo "$0: missing or empty RIR table $meta" >&2; exit 1; }
IFS=: read -r a b c <<<"$sizes"
for v in "$a" "$b" "$c"; do
  [[ "$v" =~ ^[0-9]+$ ]] || { echo "$0: --sizes must be three integers a:b:c, got '$sizes'" >&2; exit 1; }
done
dups=$(awk '{print $1}' "$meta" | sort | uniq -d | head -3)
[ -z "$dups" ] || { echo "$0: $meta: duplicate rir ids: $dups" >&2; exit 1; }
total=$(grep -c . "$meta")
if [ "$total" -eq $((a + b + c)) ]; then
  n_dev=$b; n_test=$c
else
  n_dev=$(awk -v t="$total" -v b="$b" -v s=$((a + b + c)) 'BEGIN {printf "%d", t * b / s + 0.5}')
  n_test=$(awk -v t="$total" -v c="$c" -v s=$((a + b + c)) 'BEGIN {printf "%d", t * c / s + 0.5}')
fi
n_train=$((total - n_dev - n_test))
if [ "$n_train" -lt 1 ] || [ "$n_dev" -lt 1 ] || [ "$n_test" -lt 1 ]; then
  echo "$0: $total RIRs are too few for a train/dev/test split ($n_train/$n_dev/$n_test)" >&2
  exit 1
fi
mkdir -p "$out"
awk '{print $1}' "$meta" | while read -r id; do
  printf '%s %s\n' "$(printf '%s %s' "$seed" "$id" | md5sum | cut -c1-32)" "$id"
done | sort | awk '{print $2}' >"$out/order.tmp"
head -n "$n_train" "$out/order.tmp" | sort >"$out/train.ids"
tail -n +$((n_train + 1)) "$out/order.tmp" | head -n "$n_dev" | sort >"$out/dev.ids"
tail -n +$((n_train + n_dev + 1)) "$out/order.tmp" | sort >"$out/test.ids"
rm "$out/order.tmp"
echo "total=$total train=$n_train dev=$n_dev test=$n_test seed=$seed sizes=$sizes" >"$out/split.txt"
