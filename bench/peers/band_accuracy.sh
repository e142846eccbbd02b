#!/bin/bash
# Full RIR of rir-simulate (gas) against pyroomacoustics' hybrid ISM + ray tracing of the same room
# (same absorption, scattering 0.1, no air absorption) and against Sabine/Eyring (issue 20).
# Information, not a pass mark: the models differ. All RIRs are measured by the same program
# (rir-metrics, ISO 3382 T30/EDT per octave band, broadband C50) so the measuring method is common.
#   bench/peers/band_accuracy.sh [seeds per tool (5)] [length s (2.0)]
set -euo pipefail
source "$(dirname "$0")/common.sh"
k=${1:-5}; len=${2:-2.0}
need_tsrir rir-simulate rir-metrics
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
for room in $("$PRA_PYTHON" "$peers_dir/rooms.py" list | awk '{print $1}'); do
  "$PRA_PYTHON" "$peers_dir/rooms.py" tsrir "$room" "$k" > "$tmp/$room.txt"
  "$TSRIR_BIN/rir-simulate" --length="$len" --format=float "$tmp/$room.txt" "$tmp/tsrir_$room" 2>/dev/null
  "$TSRIR_BIN/rir-metrics" --format=json "$tmp/tsrir_$room/rir.scp" > "$tmp/tsrir_$room.json"
  if have_pra; then
    for i in $(seq "$k"); do
      pra_py "$peers_dir/pra_sim.py" "$room" hybrid 1 1 "$tmp/pra_${room}_$i.wav" >/dev/null
      echo "pra_${room}_$i $tmp/pra_${room}_$i.wav"
    done > "$tmp/pra_$room.scp"
    "$TSRIR_BIN/rir-metrics" --format=json "$tmp/pra_$room.scp" > "$tmp/pra_$room.json"
  fi
done
"$PRA_PYTHON" "$peers_dir/band_table.py" "$tmp"
