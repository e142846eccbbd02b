#!/bin/bash
# rir-simulate vs pyroomacoustics (image sources only; hybrid ISM + ray tracing) vs RIR-Generator,
# same rooms, same absorption, 16 kHz (issue 20). One core, then all cores (nproc).
#   bench/peers/sim_speed.sh [N tsrir RIRs per room (1000)] [pra reps (5)] [RIR-Generator reps (1)] [tsrir reps (3)]
# tsrir: rir-simulate end to end (process start, 1.0 s RIR, float WAV + lists written), CPU time
#   (user+sys) / N, the median of `tsrir reps` runs (1000 RIRs keep the process timer's 10 ms tick
#   near 2 % of a run); peers: median time of the simulation call in their own process (imports and
#   file writing excluded), so the comparison leans in the peers' favour.
# "x" columns = peer time / tsrir time (how many times faster tsrir is).
# pyroomacoustics sets its own RIR length (ISM: up to max_order; hybrid: until the ray energy
#   threshold); pra_sim.py prints it (length_s), e.g. ISM 0.62 / 1.45 / 4.3 s, hybrid 0.46 / 0.96 / 1.9 s.
# The last two columns time tsrir gas again at pra hybrid's own RIR length (--length=length_s), the
#   same work per RIR (1.0 s is twice pra's length in the small room, half in the large one).
# All cores: tsrir --num-threads=nproc over N RIRs (wall / N); peers: nproc copies run at once,
#   wall per RIR / nproc (neither peer parallelises one RIR over cores here: pra num_threads=1).
set -euo pipefail
source "$(dirname "$0")/common.sh"
n=${1:-1000}; pra_reps=${2:-5}; rg_reps=${3:-1}; ours_reps=${4:-3}
need_tsrir rir-simulate
P=$("$peers_root/utils/cores")
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
machine_line
echo
echo "## Simulator time per RIR, 16 kHz (CPU s on one core; wall s per RIR with $P cores)"
echo "| room | tsrir gas (ism+diffuse), 1.0 s | tsrir ism only, 1.0 s | pra ISM | x | pra hybrid | x | RIR-Generator, every image of 1.0 s | x vs gas | RIR-Generator, tsrir's image set (up to its transition time) | x vs ism | tsrir gas at pra hybrid's length | x vs pra hybrid |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for room in $(room_names); do
  read -r _ dim src mic t60 alpha beta ism_samples < <("$PRA_PYTHON" "$peers_dir/rooms.py" list | awk -v r="$room" '$1 == r')
  "$PRA_PYTHON" "$peers_dir/rooms.py" tsrir "$room" "$n" > "$tmp/$room.txt"
  for mode in 1 all; do
    t=1; [ "$mode" = all ] && t=$P
    read -r w c < <(time_cmd_median "$ours_reps" "$tmp/o" "$TSRIR_BIN/rir-simulate" --length=1.0 --format=float --num-threads=$t "$tmp/$room.txt" "$tmp/o")
    read -r wi ci < <(time_cmd_median "$ours_reps" "$tmp/o" "$TSRIR_BIN/rir-simulate" --model=ism --length=1.0 --format=float --num-threads=$t "$tmp/$room.txt" "$tmp/o")
    if [ "$mode" = 1 ]; then ours=$(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.5f", c/n}'); oursi=$(awk -v c="$ci" -v n="$n" 'BEGIN{printf "%.5f", c/n}')
    else ours=$(awk -v c="$w" -v n="$n" 'BEGIN{printf "%.5f", c/n}'); oursi=$(awk -v c="$wi" -v n="$n" 'BEGIN{printf "%.5f", c/n}'); fi
    cols=()
    for pm in ism hybrid; do
      if have_pra; then
        if [ "$mode" = 1 ]; then
          pra_py "$peers_dir/pra_sim.py" "$room" $pm "$pra_reps" 1 > "$tmp/pra1"
          v=$(pra_field cpu_s_per_rir < "$tmp/pra1")
        else
          for k in $(seq $P); do pra_py "$peers_dir/pra_sim.py" "$room" $pm "$pra_reps" 1 > "$tmp/pra$k" & done; wait
          v=$(cat "$tmp"/pra* | pra_field wall_s_per_rir | awk -v p=$P '{s+=$1} END {printf "%.5f", s/NR/p}')
        fi
        [ $pm = hybrid ] && hybrid_len=$(pra_field length_s < "$tmp/pra1") && hybrid_v=$v
        cols+=("$v" "$(ratio "$ours" "$v")")
      else cols+=(absent -); fi
    done
    for ns in 16000 "$ism_samples"; do
      if have_rirgen; then
        args=(--room=$dim --src=$src --mic=$mic --beta=$beta --nsamples=$ns --order=-1 --repeat=$rg_reps -)
        if [ "$mode" = 1 ]; then v=$("$RIR_GENERATOR" "${args[@]}" | pra_field cpu_s_per_rir)
        else
          for k in $(seq $P); do "$RIR_GENERATOR" "${args[@]}" > "$tmp/rg$k" & done; wait
          v=$(cat "$tmp"/rg* | pra_field wall_s_per_rir | awk -v p=$P '{s+=$1} END {printf "%.5f", s/NR/p}')
        fi
        rm -f "$tmp"/rg*
        if [ "$ns" = 16000 ]; then cols+=("$v" "$(ratio "$ours" "$v")"); else cols+=("$v" "$(ratio "$oursi" "$v")"); fi
      else cols+=(absent -); fi
    done
    if have_pra; then
      read -r w c < <(time_cmd_median "$ours_reps" "$tmp/o" "$TSRIR_BIN/rir-simulate" --length="$hybrid_len" --format=float --num-threads=$t "$tmp/$room.txt" "$tmp/o")
      same=$(awk -v c="$([ "$mode" = 1 ] && echo "$c" || echo "$w")" -v n="$n" 'BEGIN{printf "%.5f", c/n}')
      cols+=("$same ($hybrid_len s)" "$(ratio "$same" "$hybrid_v")")
    else cols+=(absent -); fi
    rm -f "$tmp"/pra* "$tmp"/rg*
    label="$room (T60 $t60 s, alpha $alpha), $( [ "$mode" = 1 ] && echo "1 core CPU s" || echo "$P cores wall s")"
    echo "| $label | $ours | $oursi | ${cols[0]} | ${cols[1]} | ${cols[2]} | ${cols[3]} | ${cols[4]} | ${cols[5]} | ${cols[6]} | ${cols[7]} | ${cols[8]} | ${cols[9]} |"
  done
done
echo
echo "x = peer time / tsrir time. pra columns and RIR-Generator's full 1 s RIR divide by tsrir gas (each a"
echo "complete 1 s RIR; RIR-Generator has no diffuse model, so it needs every image); RIR-Generator on"
echo "tsrir's image set (nsamples = the ism_samples column of rooms.py list, order -1) divides by tsrir ism only."
echo "Load after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
