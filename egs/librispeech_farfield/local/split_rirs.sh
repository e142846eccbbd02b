#!/usr/bin/env bash
# Splits a real-RIR metadata table (<rir-id> <room-id> ...) into train/dev/test, the paper's
# 773/194/242 split of BUT ReverbDB (TS-RIR sec. 4.2: "We randomly split 1209 RIRs ... into subsets
# of {773,194,242}"). The split is a seeded random permutation that depends only on (seed, rir id):
# RIRs are ordered by md5("<seed> <rir-id>") and cut in that order, so it is reproducible on any
# machine and independent of the table's order. When the table does not hold exactly the sum of
# --sizes RIRs, the sizes are scaled to its count (dev and test rounded, train = the rest).
# --group-fields "6 7 8" splits whole groups instead of single RIRs: the RIRs whose metadata agree
# in those fields (here the source position x y z) share a group, groups are ordered by
# md5("<seed> <key>") and train, then dev are filled group by group up to their sizes, the rest is
# test (without groups: exactly the split by single RIRs described above). So no source position has RIRs in two splits, whatever room condition it was measured in
# (a test position's siblings from other conditions would otherwise be in training). The sizes are
# then approximate (whole groups); split.txt says what they came out as.
# Writes <out-dir>/{train,dev,test}.ids (sorted) and <out-dir>/split.txt (the sizes used).
set -euo pipefail
seed=0
sizes=773:194:242
group_fields=""
help_message="Usage: $0 [--seed N] [--sizes train:dev:test] [--group-fields \"6 7 8\"] <meta.txt> <out-dir>"
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
mkdir -p "$out"
for f in $group_fields; do
  [[ "$f" =~ ^[0-9]+$ ]] && [ "$f" -ge 1 ] || { echo "$0: --group-fields must list field numbers, got '$group_fields'" >&2; exit 1; }
done
# "<group key> <rir id>" per RIR; without --group-fields each RIR is its own group.
awk -v fields="$group_fields" 'BEGIN { n = split(fields, f, " ") }
  { key = ""; for (i = 1; i <= n; i++) key = key (i > 1 ? "_" : "") $f[i]; if (n == 0) key = $1; print key, $1 }' \
  "$meta" >"$out/groups.tmp"
awk '{print $1}' "$out/groups.tmp" | sort -u | while read -r key; do
  printf '%s %s\n' "$(printf '%s %s' "$seed" "$key" | md5sum | cut -c1-32)" "$key"
done | sort | awk '{print $2}' >"$out/order.tmp"
# Whole groups in that order: train first, then dev, each until it holds at least its size.
awk -v nr="$n_train" -v nd="$n_dev" 'NR == FNR { size[$1]++; members[$1] = members[$1] " " $2; next }
  { part = (r < nr) ? "train" : (d < nd) ? "dev" : "test"
    if (part == "train") r += size[$1]; else if (part == "dev") d += size[$1]
    m = split(members[$1], ids, " "); for (i = 1; i <= m; i++) print part, ids[i] }' \
  "$out/groups.tmp" "$out/order.tmp" >"$out/assign.tmp"
for split in train dev test; do awk -v s="$split" '$1 == s {print $2}' "$out/assign.tmp" | sort >"$out/$split.ids"; done
n_train=$(wc -l <"$out/train.ids"); n_dev=$(wc -l <"$out/dev.ids"); n_test=$(wc -l <"$out/test.ids")
if [ "$n_train" -lt 1 ] || [ "$n_dev" -lt 1 ] || [ "$n_test" -lt 1 ]; then
  echo "$0: $total RIRs in $(wc -l <"$out/order.tmp") groups are too few for a train/dev/test split ($n_train/$n_dev/$n_test)" >&2
  exit 1
fi
rm "$out/order.tmp" "$out/groups.tmp" "$out/assign.tmp"
echo "total=$total train=$n_train dev=$n_dev test=$n_test seed=$seed sizes=$sizes${group_fields:+ groups=fields $group_fields}" >"$out/split.txt"
