# Shared by bench/gan's speed scripts (sourced): their work directory and bench set, a training
# step's median, one measured gas-to-real run and the run's header lines.

# The repository root, found once from this file's place (bench/gan/).
speed_lib_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

# A temporary $work (removed at exit) holding the bench set, $n its RIRs.
bench_setup() {
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  r3vival_scp "$speed_lib_root/../shared/data/rirs/r3vival"
  n=$(wc -l < "$work/rir.scp")
}

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

# One measured gas-to-real run: label bin batch [model directory, default $work/m64] [its width as
# printed, default 64] -> one line (whole process, CPU, RSS).
translate_row() {
  local label=$1 bin=$2 batch=$3 model=${4:-$work/m64} width=${5:-64} wall user sys rss
  rm -rf "$work/out"
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$bin/gas-to-real" --model="$model" --batch-size="$batch" \
    --num-threads=2 "$work/rir.scp" "$work/out" 2> "$work/log"
  read -r wall user sys rss < "$work/time"
  echo "$label: gas-to-real width $width, batch $batch: whole process $wall s ($(awk -v w="$wall" -v n="$n" \
    'BEGIN{printf "%.1f", n / w}') RIRs/s), user $user s, sys $sys s, peak RSS $((rss / 1024)) MB;" \
    "$(grep -o 'model load [0-9.e-]* s, [0-9.]* RIRs/s' "$work/log")"
}

# The run's first two lines: when, where (cores without OMP_NUM_THREADS, which nproc honours; CPU
# model, family and model number), which programs and commit (-dirty: with uncommitted changes); the
# load average before.
bench_header() {
  local bin=$1
  cpu_field() { grep -m1 "$1" /proc/cpuinfo | cut -d: -f2 | xargs; }
  echo "# $(date -u +%Y-%m-%dT%H:%MZ) $(uname -n), $("$speed_lib_root/utils/cores") cores," \
    "$(cpu_field 'model name'), family $(cpu_field 'cpu family') model $(cpu_field '^model\s'); $bin;" \
    "git $(git -C "$speed_lib_root" describe --always --dirty)"
  echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
}
