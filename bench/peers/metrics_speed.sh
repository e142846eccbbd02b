#!/bin/bash
# rir-metrics vs pyroomacoustics' measure_rt60, per RIR, on the same RIRs (issue 20).
#   bench/peers/metrics_speed.sh [RIRs per room (1000)] [repetitions (3)]
# RIRs: rir-simulate gas, 1.0 s, float WAV, the three rooms of rooms.txt.
# tsrir: `rir-metrics --bands` process CPU (user+sys; reading included; all octave bands T20/T30/EDT,
# DRR, C50) / N. pyroomacoustics: CPU of measure_rt60 (one broadband RT60 from a 30 dB decay,
# extrapolated to 60 dB), file reading excluded. Values side by side: rir-metrics' T60 is ISO
# (mean T30 of the 500 Hz and 1 kHz bands); pra's is broadband, so they differ by definition.
# Each side runs `repetitions` times, alternating, and each column is the median: on a shared VM one
# run of either moves by +-30 %. 1000 RIRs keep the process timer's 10 ms tick below 2 % of ours.
set -euo pipefail
source "$(dirname "$0")/common.sh"
n=${1:-1000}; reps=${2:-3}
need_tsrir rir-simulate rir-metrics
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
echo
echo "## Metrics time per 1 s RIR at 16 kHz, one core (CPU ms; median of $reps alternating runs of $n RIRs)"
echo "| room | rir-metrics --bands (all bands, incl. reading) | pra measure_rt60 (broadband only) | x | mean T60 rir-metrics (ISO, 500-1k T30) | mean RT60 pra (broadband, 30 dB) | runs: rir-metrics / pra |"
echo "|---|---|---|---|---|---|---|"
for room in $("$PRA_PYTHON" "$peers_dir/rooms.py" list | awk '{print $1}'); do
  "$PRA_PYTHON" "$peers_dir/rooms.py" tsrir "$room" "$n" > "$tmp/$room.txt"
  "$TSRIR_BIN/rir-simulate" --length=1.0 --format=float "$tmp/$room.txt" "$tmp/$room" 2>/dev/null
  ours_runs=() pra_runs=()
  for ((r = 0; r < reps; r++)); do
    read -r w c < <(time_cmd "$TSRIR_BIN/rir-metrics" --bands "$tmp/$room/rir.scp")
    ours_runs+=("$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.4f", 1000*c/n}')")
    if have_pra; then
      pra_py "$peers_dir/pra_rt60.py" "$tmp/$room/rir.scp" > "$tmp/pra.txt"
      pra_runs+=("$(sed -n 's/cpu_s_per_rir=//p' "$tmp/pra.txt" | awk '{printf "%.4f", 1000*$1}')")
    fi
  done
  ours=$(median "${ours_runs[@]}")
  t60=$("$TSRIR_BIN/rir-metrics" "$tmp/$room/rir.scp" 2>/dev/null | awk '$1 !~ /^#/ && NF > 2 {s += $2; k++} END {printf "%.3f", s/k}')
  if have_pra; then
    p=$(median "${pra_runs[@]}")
    pt=$(grep -v cpu_s "$tmp/pra.txt" | awk '{s += $2; k++} END {printf "%.3f", s/k}')
    echo "| $room | $ours | $p | $(ratio "$ours" "$p") | $t60 | $pt | ${ours_runs[*]} / ${pra_runs[*]} |"
  else
    echo "| $room | $ours | absent | - | $t60 | absent | ${ours_runs[*]} |"
  fi
done
echo "Load after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
