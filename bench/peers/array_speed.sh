#!/bin/bash
# Microphone arrays against pyroomacoustics (issue 33, item 5): per source position, the CPU time of
# one microphone and of an 8-microphone circular array (radius 5 cm, horizontal, centred on the
# room's mic) in the three rooms of rooms.txt, for rir-simulate (gas, 1.0 s RIRs, float WAVs
# written, process start included, CPU s / N) and pyroomacoustics' hybrid model (ISM order 3 +
# ray tracing, pra's defaults; the median CPU time of Room.compute_rir() in its own process,
# imports and room set-up excluded, so the comparison leans in the peer's favour), in one run.
#   bench/peers/array_speed.sh [N tsrir source positions per room (100)] [pra reps (3)]
# Goals (issue 33): tsrir 8 mics <= 2x one mic; pra hybrid 8 mics / tsrir 8 mics >= 50.
# pyroomacoustics' hybrid model sets its own RIR length (until the ray energy threshold: 0.46 / 0.96
# / 1.9 s in these rooms), so the last columns time tsrir's 8 mics again at that length (--length=
# pra's length_s), the same work per RIR: 1.0 s is twice pra's length in the small room, half in the large.
set -euo pipefail
source "$(dirname "$0")/common.sh"
n=${1:-100}; pra_reps=${2:-3}
need_tsrir rir-simulate
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
printf 'circular n=8 radius_m=0.05\n' > "$tmp/circular8.txt"
echo
echo "## CPU s per source position, 16 kHz, one core"
echo "| room | tsrir 1 mic | tsrir 8 mics | tsrir 8/1 | pra hybrid 1 mic | pra hybrid 8 mics | pra 8/1 | pra 8 mics / tsrir 8 mics | pra's RIR length s | tsrir 8 mics at that length | pra 8 mics / tsrir 8 mics, same length |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for room in $(room_names); do
  "$PRA_PYTHON" "$peers_dir/rooms.py" tsrir "$room" "$n" > "$tmp/one.txt"
  sed 's/ absorption=/ array=circular8.txt absorption=/' "$tmp/one.txt" > "$tmp/eight.txt"
  cols=()
  for list in one eight; do
    rm -rf "$tmp/o"
    read -r _ c < <(cd "$tmp" && time_cmd "$TSRIR_BIN/rir-simulate" --length=1.0 --format=float --num-threads=1 "$list.txt" o)
    cols+=("$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.5f", c/n}')")
  done
  if have_pra; then
    for m in 1 8; do pra_py "$peers_dir/pra_sim.py" "$room" hybrid "$pra_reps" 1 --mics=$m > "$tmp/pra$m"; done
    cols+=("$(pra_field cpu_s_per_rir < "$tmp/pra1")" "$(pra_field cpu_s_per_rir < "$tmp/pra8")")
    pra_len=$(pra_field length_s < "$tmp/pra8")
    rm -rf "$tmp/o"
    read -r _ c < <(cd "$tmp" && time_cmd "$TSRIR_BIN/rir-simulate" --length="$pra_len" --format=float --num-threads=1 eight.txt o)
    cols+=("$pra_len" "$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.5f", c/n}')")
  else cols+=(absent absent absent absent); fi
  echo "| $room | ${cols[0]} | ${cols[1]} | $(ratio "${cols[0]}" "${cols[1]}") | ${cols[2]} | ${cols[3]} | $(ratio "${cols[2]}" "${cols[3]}") | $(ratio "${cols[1]}" "${cols[3]}") | ${cols[4]} | ${cols[5]} | $(ratio "${cols[5]}" "${cols[3]}") |"
done
echo
echo "Ratios: 'a/b' columns = b / a. Load after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
