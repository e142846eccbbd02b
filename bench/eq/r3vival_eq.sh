#!/usr/bin/env bash
# Regenerates the numbers of docs/eq-r3vival.md: fit the EQ on measured R3VIVAL RIRs (3 of the 5
# panel conditions, resampled to 16 kHz), simulate the same room with rir-simulate, equalize the
# simulated RIRs, and print the per-point relative gains (dB re 1 kHz, mean / std) of real,
# simulated and simulated+EQ RIRs as markdown tables.
#
# Usage: bench/eq/r3vival_eq.sh [build-dir (default: build)] [work-dir (default: exp/eq-r3vival)]
# Needs ../shared/data/rirs/r3vival next to the repository and the built rir-simulate and rir-eq.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
work=${2:-$root/exp/eq-r3vival}
data=$root/../shared/data/rirs/r3vival
bin=$build/bin
fit_conditions="000 050 100"
heldout_conditions="025 075"   # not used for fitting: does the EQ carry over to other states of the room?
[ -d "$data" ] || { echo "r3vival_eq.sh: $data not found" >&2; exit 1; }
for p in rir-simulate rir-eq; do [ -x "$bin/$p" ] || { echo "r3vival_eq.sh: $bin/$p not built" >&2; exit 1; }; done
# Outputs in $work are overwritten (output sets are replaced atomically by the programs).
mkdir -p "$work"

# 1. Measured RIRs (ids: c<cond>_<source>).
real_scp() {
  for c in "$@"; do
    for f in "$data"/RLRVarAcLab_Absorptive_${c}_*_R1_FRL10cm_ch7.wav; do
      s=$(basename "$f" | sed -E 's/^RLRVarAcLab_Absorptive_[0-9]+_(.*)_R1_FRL10cm_ch7\.wav$/\1/')
      echo "c${c}_$s $f"
    done
  done | LC_ALL=C sort
}
real_scp $fit_conditions > "$work/real.scp"
real_scp $heldout_conditions > "$work/real_heldout.scp"

# 2. The same room in rir-simulate: 9.7 x 5.5 x 2.7 m, receiver R1, the 34 source positions (x, y
# read off the published plan; heights are not published: 1.35 m for sources and microphone),
# per condition the measured octave T30 (250 Hz value also for 62.5/125 Hz, 4 kHz also for 8 kHz).
room_list() {
awk -F, -v conds="$*" '
  FNR == 1 { next }
  FILENAME ~ /T30/ { t[$1] = $3 "," $3 "," $3 "," $4 "," $5 "," $6 "," $7 "," $7; next }
  $1 ~ /^R1/ { next }
  { src[$1] = $4 "," $5 ",1.35"; order[++n] = $1 }
  END {
    split(conds, cs, " ")
    for (i = 1; i <= length(cs); ++i)
      for (k = 1; k <= n; ++k)
        printf "c%s_%s room=9.7,5.5,2.7 src=%s mic=6.20,2.75,1.35 t60=%s room-id=r3vival_%s\n", cs[i], order[k], src[order[k]], t[cs[i]], cs[i]
  }' "$data/T30_per_condition_estimated.csv" "$data/positions_approx_from_Plan_png.csv"
}
room_list $fit_conditions > "$work/rooms.txt"
room_list $heldout_conditions > "$work/rooms_heldout.txt"
"$bin/rir-simulate" --fs=16000 --length=1.0 --seed=1 --num-threads=2 "$work/rooms.txt" "$work/sim" 2>"$work/simulate.log"
"$bin/rir-simulate" --fs=16000 --length=1.0 --seed=2 --num-threads=2 "$work/rooms_heldout.txt" "$work/sim_heldout" \
  2>>"$work/simulate.log"

# 3. Fit on the measured RIRs (resampled 48 -> 16 kHz), apply to the simulated ones.
"$bin/rir-eq" fit --sample-rate=16000 "$work/real.scp" "$work/indep.model" 2>"$work/fit_indep.log"
"$bin/rir-eq" fit --sample-rate=16000 --model=gmm --components=2 --covariance=full --seed=1 \
  "$work/real.scp" "$work/gmm.model" 2>"$work/fit_gmm.log"
"$bin/rir-eq" apply --seed=1 --num-threads=2 "$work/indep.model" "$work/sim/rir.scp" "$work/sim_eq_indep" 2>"$work/apply_indep.log"
"$bin/rir-eq" apply --seed=1 --num-threads=2 "$work/gmm.model" "$work/sim/rir.scp" "$work/sim_eq_gmm" 2>"$work/apply_gmm.log"
"$bin/rir-eq" apply --seed=2 --num-threads=2 "$work/indep.model" "$work/sim_heldout/rir.scp" "$work/sim_heldout_eq_indep" \
  2>"$work/apply_heldout_indep.log"

# 4. Relative gains of every set, measured the same way (octave-band power, 16 kHz).
"$bin/rir-eq" gains --sample-rate=16000 "$work/real.scp" "$work/real.gains" 2>/dev/null
"$bin/rir-eq" gains --sample-rate=16000 "$work/real_heldout.scp" "$work/real_heldout.gains" 2>/dev/null
for s in sim sim_eq_indep sim_eq_gmm sim_heldout sim_heldout_eq_indep; do "$bin/rir-eq" gains "$work/$s/rir.scp" "$work/$s.gains" 2>/dev/null; done

# 5. Tables: per point mean / std, and the gap |mean - real mean|.
stats() {  # file -> 7 lines "mean std"
  awk '!/^#/ { for (k = 2; k <= 8; ++k) { s[k] += $k; q[k] += $k * $k } ++n }
       END { for (k = 2; k <= 8; ++k) { m = s[k] / n; v = (q[k] - n * m * m) / (n - 1); printf "%.2f %.2f\n", m, sqrt(v > 0 ? v : 0) } }' "$1"
}
paste -d' ' <(printf '%s\n' 62.5 125 250 500 2000 4000 8000) <(stats "$work/real.gains") <(stats "$work/sim.gains") \
  <(stats "$work/sim_eq_indep.gains") <(stats "$work/sim_eq_gmm.gains") > "$work/table.txt"
paste -d' ' <(printf '%s\n' 62.5 125 250 500 2000 4000 8000) <(stats "$work/real_heldout.gains") \
  <(stats "$work/sim_heldout.gains") <(stats "$work/sim_heldout_eq_indep.gains") > "$work/table_heldout.txt"
n_real=$(grep -vc '^#' "$work/real.gains"); n_sim=$(grep -vc '^#' "$work/sim.gains")
{
  echo "Relative gain (dB re 1 kHz), mean / std over RIRs: real = R3VIVAL conditions $fit_conditions ($n_real RIRs," \
       "48 kHz resampled to 16 kHz); sim = rir-simulate ($n_sim RIRs); sim+EQ = after rir-eq apply."
  echo
  echo "| point (Hz) | real | sim | sim+EQ (indep) | sim+EQ (GMM, 2 full) |"
  echo "|---|---|---|---|---|"
  awk '{ printf "| %s | %s / %s | %s / %s | %s / %s | %s / %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9 }' "$work/table.txt"
  echo
  echo "Gap |mean - real mean| (dB):"
  echo
  echo "| point (Hz) | sim | sim+EQ (indep) | sim+EQ (GMM) |"
  echo "|---|---|---|---|"
  awk 'function a(x) { return x < 0 ? -x : x }
       { printf "| %s | %.2f | %.2f | %.2f |\n", $1, a($4 - $2), a($6 - $2), a($8 - $2); g0 += a($4 - $2); g1 += a($6 - $2); g2 += a($8 - $2) }
       END { printf "| mean | %.2f | %.2f | %.2f |\n", g0 / NR, g1 / NR, g2 / NR }' "$work/table.txt"
  echo
  echo "Held-out conditions $heldout_conditions ($(grep -vc '^#' "$work/real_heldout.gains") measured RIRs, not used by the fit;" \
       "simulated with their own T30), equalized with the model fitted above (indep):"
  echo
  echo "| point (Hz) | real | sim | sim+EQ | gap sim | gap sim+EQ |"
  echo "|---|---|---|---|---|---|"
  awk 'function a(x) { return x < 0 ? -x : x }
       { printf "| %s | %s / %s | %s / %s | %s / %s | %.2f | %.2f |\n", $1, $2, $3, $4, $5, $6, $7, a($4 - $2), a($6 - $2); g0 += a($4 - $2); g1 += a($6 - $2) }
       END { printf "| mean | | | | %.2f | %.2f |\n", g0 / NR, g1 / NR }' "$work/table_heldout.txt"
} | tee "$work/report.md"
