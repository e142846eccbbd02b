#!/bin/bash
# rir-simulate's CPU time per RIR against the RIR length (--length), one or two builds side by side
# (interleaved, best of 3): the FFT sizes that lengths lead to (dsp/fft.h, next_fast_fft_size) matter.
#   bench/sim/length_sweep.sh <bin-dir A> [<bin-dir B>] [positions (200)] [lengths ("0.80 0.84 ... 1.00")]
# The reference room of bench/peers/rooms.txt, positions as bench/peers/rooms.py draws them, one mic
# and an 8-mic circular array (radius 5 cm), gas, float WAVs, one thread; CPU = user + sys / positions.
set -euo pipefail
a=$(cd "$1" && pwd); b=${2:+$(cd "$2" && pwd)}; n=${3:-200}
lengths=${4:-"0.80 0.84 0.85 0.88 0.894 0.90 0.92 0.94 0.96 0.98 1.00"}
here=$(cd "$(dirname "$0")" && pwd)
py=$( [ -x /usr/bin/python3 ] && echo /usr/bin/python3 || echo python3)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$py" "$here/../peers/rooms.py" tsrir reference "$n" > "$tmp/one.txt"
printf 'circular n=8 radius_m=0.05\n' > "$tmp/circular8.txt"
sed 's/ absorption=/ array=circular8.txt absorption=/' "$tmp/one.txt" > "$tmp/eight.txt"
echo "machine: $("$here/../../utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u '+%F %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
cpu_ms() {  # <bin> <list> <length>: best of 3, ms per position
  local best=""
  for _ in 1 2 3; do
    rm -rf "$tmp/o"
    (cd "$tmp" && /usr/bin/time -f "%U %S" -o t "$1/rir-simulate" --length="$3" --format=float --num-threads=1 "$2" o >/dev/null 2>&1) ||
      { echo "rir-simulate failed: $1 $2 --length=$3" >&2; exit 1; }
    local v; v=$(awk -v n="$n" '{printf "%.3f", ($1 + $2) * 1000 / n}' "$tmp/t")
    best=$(awk -v a="$best" -v b="$v" 'BEGIN { print (a == "" || b < a) ? b : a }')
  done
  echo "$best"
}
echo "| length s | samples | 1 mic, A | 8 mics, A |${b:+ 1 mic, B | 8 mics, B |}"
echo "|---|---|---|---|${b:+---|---|}"
for len in $lengths; do
  row="| $len | $(awk -v l="$len" 'BEGIN{printf "%d", l * 16000 + 0.5}') |"
  for bin in $a $b; do  # an assignment keeps a failed substitution's status: a failed run ends the script
    for list in one.txt eight.txt; do v=$(cpu_ms "$bin" $list "$len") || exit 1; row+=" $v |"; done
  done
  echo "$row"
done
echo "A = $a${b:+, B = $b}. Load after: $(cut -d' ' -f1-3 /proc/loadavg)"
