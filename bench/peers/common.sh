# Sourced by the bench/peers scripts: finds tsrir's programs and the peers (never builds a peer).
#   TSRIR_BIN      tsrir's bin dir (default <repo>/build/bin; built with ninja if missing)
#   KALDI_ROOT     a Kaldi checkout with src/featbin built
#   PRA_PYTHONPATH pyroomacoustics source tree with libroom compiled in place
#   PRA_PYTHON     python3 with numpy/scipy (default: /usr/bin/python3 if present, else python3)
#   RIR_GENERATOR  command-line build of RIR-Generator's computeRIR (see bench/peers/README.md)
# A peer that is not found makes its rows print "absent".
peers_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
peers_dir=$peers_root/bench/peers
TSRIR_BIN=${TSRIR_BIN:-$peers_root/build/bin}
PRA_PYTHON=${PRA_PYTHON:-$( [ -x /usr/bin/python3 ] && echo /usr/bin/python3 || echo python3)}

need_tsrir() {
  local missing=()
  for p in "$@"; do [ -x "$TSRIR_BIN/$p" ] || missing+=("$p"); done
  if [ ${#missing[@]} -gt 0 ]; then
    if [ -f "$peers_root/build/build.ninja" ] && [ "$TSRIR_BIN" = "$peers_root/build/bin" ]; then
      ninja -C "$peers_root/build" "${missing[@]}" >&2
    else
      echo "tsrir programs missing in $TSRIR_BIN: ${missing[*]} (set TSRIR_BIN)" >&2; exit 1
    fi
  fi
}

have_pra() {
  [ -n "${PRA_PYTHONPATH:-}" ] && PYTHONPATH=$PRA_PYTHONPATH "$PRA_PYTHON" -c 'import pyroomacoustics.libroom' 2>/dev/null
}
have_kaldi() { [ -n "${KALDI_ROOT:-}" ] && [ -x "$KALDI_ROOT/src/featbin/wav-reverberate" ]; }
have_rirgen() { [ -n "${RIR_GENERATOR:-}" ] && [ -x "$RIR_GENERATOR" ]; }
pra_py() { PYTHONPATH=$PRA_PYTHONPATH "$PRA_PYTHON" "$@"; }
# The value of `name=value` in a peer script's result line (pra_sim.py, RIR-Generator's CLI).
pra_field() { sed -n "s/.*$1=\([0-9.]*\).*/\1/p"; }
# The names of rooms.txt's rooms.
room_names() { "$PRA_PYTHON" "$peers_dir/rooms.py" list | awk '{print $1}'; }

# The kind of CPU, for bench/peers/results/<kind>/: intel, amd, or the vendor id in lower case.
machine_kind() {
  local v; v=$(grep -m1 'vendor_id' /proc/cpuinfo | cut -d: -f2 | tr -d ' ')
  case $v in GenuineIntel) echo intel ;; AuthenticAMD) echo amd ;; *) echo "${v,,}" | tr -cd 'a-z0-9_-' ;; esac
}

machine_line() {
  echo "machine: $("$peers_root/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u '+%F %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg), temporary files on $(df -T "${TMPDIR:-/tmp}" | awk 'NR == 2 { print $2 }')"
  echo "peers: KALDI_ROOT=${KALDI_ROOT:-unset} PRA_PYTHONPATH=${PRA_PYTHONPATH:-unset} RIR_GENERATOR=${RIR_GENERATOR:-unset}"
}

# "<wall_s> <cpu_s>" of a command (user+sys of it and its children).
time_cmd() {
  local f; f=$(mktemp)
  /usr/bin/time -f "%e %U %S" -o "$f" "$@" >/dev/null 2>&1 || { echo "command failed: $*" >&2; rm -f "$f"; return 1; }
  awk '{ printf "%s %.6f\n", $1, $2 + $3 }' "$f"; rm -f "$f"
}
# "<wall_s> <cpu_s>": the medians of REPS runs of a command, OUT_DIR (its output) removed before each.
time_cmd_median() {
  local reps=$1 out=$2 walls=() cpus=() w c; shift 2
  for ((k = 0; k < reps; k++)); do
    rm -rf "$out"; read -r w c < <(time_cmd "$@"); walls+=("$w"); cpus+=("$c")
  done
  echo "$(median "${walls[@]}") $(median "${cpus[@]}")"
}
# The median of its numeric arguments (the mean of the middle two for an even count).
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { printf "%.6g", NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (a == "" || b == "" || a <= 0) print "-"; else printf "%.1fx\n", b / a }'; }
