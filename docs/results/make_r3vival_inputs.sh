#!/bin/bash
# Builds the inputs of the R3VIVAL diagnosis: a room list (stated set-ups, the baseline's prior)
# and an scp of the 170 measured RIRs. Reads the data in place.
#   usage: docs/results/make_r3vival_inputs.sh <r3vival-dir> <out-dir>
# Stated set-up (documented assumptions, none taken from the measured responses):
#  - room 9.7 x 5.5 x 2.7 m; x, y of sources and receiver from positions_approx_from_Plan_png.csv
#    (read off the published plan, +-0.1 m);
#  - heights are not published: source and microphone at 1.35 m (the middle of the 1.2-1.5 m the
#    dataset notes suggest);
#  - absorption prior: one flat T60 per panel condition, interpolated linearly across the 0-100 %
#    absorptive-panel settings between the 0.75 s and 0.5 s the dataset's description gives as the
#    range of its mid-frequency RT60 (000: 0.75 s ... 100: 0.5 s); no band dependence is assumed,
#    so band_absorption has to find it;
#  - scattering 0.1 (the simulator's default), 20 C, 50 % RH; room id = panel condition.
set -euo pipefail
src=${1:?r3vival dir}
out=${2:?out dir}
mkdir -p "$out"
csv="$src/positions_approx_from_Plan_png.csv"
[ -f "$csv" ] || { echo "$0: $csv not found" >&2; exit 1; }
rooms="$out/rooms.txt"
scp="$out/rir.scp"
: > "$rooms.tmp"
: > "$scp.tmp"
read -r rx ry < <(awk -F, '/receiver/ {print $4, $5}' "$csv")
for cond in 000 025 050 075 100; do
  t60=$(awk -v c="$cond" 'BEGIN { printf "%.4f", 0.75 - 0.25 * (c + 0) / 100 }')
  awk -F, -v cond="$cond" -v t60="$t60" -v rx="$rx" -v ry="$ry" -v dir="$src" '
    NR > 1 && $6 != "receiver" && $1 !~ /^R1/ {
      id = "RLRVarAcLab_Absorptive_" cond "_" ($1 ~ /^S/ ? $1 : "S" $1) "_R1_FRL10cm_ch7"
      printf "%s room=9.7,5.5,2.7 src=%s,%s,1.35 mic=%s,%s,1.35 t60=%s scattering=0.1 room-id=cond%s\n", id, $4, $5, rx, ry, t60, cond
    }' "$csv" >> "$rooms.tmp"
done
while read -r id rest; do
  f="$src/$id.wav"
  [ -f "$f" ] || { echo "$0: missing $f" >&2; exit 1; }
  echo "$id $(cd "$(dirname "$f")" && pwd)/$(basename "$f")" >> "$scp.tmp"
done < "$rooms.tmp"
sort "$rooms.tmp" > "$rooms" && rm "$rooms.tmp"
sort "$scp.tmp" > "$scp" && rm "$scp.tmp"
echo "$0: $(wc -l < "$rooms") set-ups in $rooms, $(wc -l < "$scp") RIRs in $scp" >&2
