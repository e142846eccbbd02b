#!/bin/bash
# R3VIVAL: per-band T30 of rir-simulate against the measured RIRs on held-out positions (issue 20).
#   bench/peers/r3vival_t30.sh [r3vival dir (../shared/data/rirs/r3vival)]
# 1. docs/results/make_r3vival_inputs.sh: stated set-up (room, positions, flat T60 prior per condition).
# 2. rir-diagnose fits its model extensions on half of the 170 RIRs (ids sorted by room, alternating:
#    1st, 3rd, ... fit) and writes extended_models; the absorption it fitted is the band_absorption
#    (+ scattering) part of that file, read here as the program wrote it.
# 3. The other 85 positions (2nd, 4th, ...) are simulated with: the baseline gas (stated flat T60),
#    gas + the fitted band_absorption and scattering, and the full extended model; all RIRs, measured
#    and simulated, are measured by rir-metrics (ISO T30 per octave band).
# Measured RIRs are read in place.
set -euo pipefail
source "$(dirname "$0")/common.sh"
data=${1:-$peers_root/../shared/data/rirs/r3vival}
[ -d "$data" ] || { echo "$0: $data not found (the workplace's R3VIVAL RIRs); skipped" >&2; exit 0; }
need_tsrir rir-simulate rir-metrics rir-diagnose
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
"$peers_root/docs/results/make_r3vival_inputs.sh" "$data" "$tmp/in" 2>/dev/null
"$TSRIR_BIN/rir-diagnose" --fs=16000 --model=gas --seed=1 --num-threads=2 "$tmp/in/rooms.txt" "$tmp/in/rir.scp" "$tmp/diag" > "$tmp/diag.log" 2>&1
awk 'NR % 2 == 0' "$tmp/in/rooms.txt" > "$tmp/heldout.txt"   # rooms.txt is sorted by (condition, id)
awk 'NR % 2 == 0' "$tmp/in/rir.scp" > "$tmp/measured.scp"
"$TSRIR_BIN/rir-metrics" --format=json "$tmp/measured.scp" > "$tmp/measured.json"
for variant in baseline fitted_absorption extended; do
  : > "$tmp/$variant.scp"
  for cond in 000 025 050 075 100; do
    grep " room-id=cond$cond\$" "$tmp/heldout.txt" > "$tmp/h$cond.txt" || continue
    full=$(awk -v r="cond$cond" '$1 == r {print $2}' "$tmp/diag/extended_models")
    case $variant in
      baseline) model=gas ;;
      fitted_absorption) model=$(echo "$full" | tr '+' '\n' | grep -E '^(gas|band_absorption|scattering)' | paste -sd+) ;;
      extended) model=$full ;;
    esac
    echo "cond$cond $variant $model" >> "$tmp/models.txt"
    "$TSRIR_BIN/rir-simulate" --fs=16000 --length=1.0 --format=float --seed=3 --model="$model" "$tmp/h$cond.txt" "$tmp/sim_${variant}_$cond" 2>/dev/null
    cat "$tmp/sim_${variant}_$cond/rir.scp" >> "$tmp/$variant.scp"
  done
  "$TSRIR_BIN/rir-metrics" --format=json "$tmp/$variant.scp" > "$tmp/$variant.json"
done
echo "models (from rir-diagnose's extended_models):"; sed 's/^/  /' "$tmp/models.txt" | cut -c1-160
"$PRA_PYTHON" "$peers_dir/r3vival_table.py" "$tmp"
