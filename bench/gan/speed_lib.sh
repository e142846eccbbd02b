# Shared by bench/gan/compare_builds.sh and checkpoint_cost_and_speed.sh (sourced; `work` and `n`
# set by the caller): the bench set, a training step's median and one measured gas-to-real run.

# The 170 measured R3VIVAL RIRs (48 kHz, resampled by the programs) as a Kaldi list in $work.
r3vival_scp() {
  local data=$1
  [[ -d $data ]] || { echo "needs ../shared/data/rirs/r3vival (real RIRs)" >&2; exit 1; }
  for f in "$data"/*.wav; do echo "$(basename "$f" .wav) $f"; done > "$work/rir.scp"
}

# Median step_s of steps 3-12 of a loss log (steps 1-2 carry one-time set-up).
median_step() {
  awk -F, 'NR>3{print $NF}' "$1" | sort -g | awk '{a[NR]=$1} END{print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'
}

# One measured gas-to-real run on $work/m64: label bin batch -> one line (whole process, CPU, RSS).
translate_row() {
  local label=$1 bin=$2 batch=$3 wall user sys rss
  rm -rf "$work/out"
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$bin/gas-to-real" --model="$work/m64" --batch-size="$batch" \
    --num-threads=2 "$work/rir.scp" "$work/out" 2> "$work/log"
  read -r wall user sys rss < "$work/time"
  echo "$label: gas-to-real width 64, batch $batch: whole process $wall s ($(awk -v w="$wall" -v n="$n" \
    'BEGIN{printf "%.1f", n / w}') RIRs/s), user $user s, sys $sys s, peak RSS $((rss / 1024)) MB;" \
    "$(grep -o 'model load [0-9.e-]* s, [0-9.]* RIRs/s' "$work/log")"
}
