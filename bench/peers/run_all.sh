#!/bin/bash
# Runs every side-by-side benchmark and accuracy comparison, writes bench/peers/results/<kind>/<name>.txt
# (<kind>: this machine's CPU, intel or amd: common.sh's machine_kind), then regenerates the summary at the
# top of bench/RESULTS.md (summary.py), which has a row per comparison and machine kind.
#   bench/peers/run_all.sh [quick]      (quick: fewer repetitions, for a smoke run)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/common.sh"
out_dir=$here/results/$(machine_kind)
mkdir -p "$out_dir"
q=${1:-}
run() {  # name, command...
  local name=$1; shift
  echo "== $name: $*" >&2
  { echo "\$ ${*//$peers_root\//}"; "$@"; } > "$out_dir/$name.txt.tmp" 2>&1 && mv "$out_dir/$name.txt.tmp" "$out_dir/$name.txt"
}
if [ "$q" = quick ]; then
  run sim_speed "$here/sim_speed.sh" 50 1 1
  run array_speed "$here/array_speed.sh" 50 1
  run metrics_speed "$here/metrics_speed.sh" 50
  run reverb_speed "$here/reverb_speed.sh" 20 10
  run pipes_vs_kaldi "$here/../augment/pipes_vs_kaldi.sh" "$TSRIR_BIN" 100
  run datadir_speed "$here/datadir_speed.sh" 10 10
  run band_accuracy "$here/band_accuracy.sh" 2
else
  run sim_speed "$here/sim_speed.sh"
  run array_speed "$here/array_speed.sh"
  run metrics_speed "$here/metrics_speed.sh"
  run reverb_speed "$here/reverb_speed.sh"
  run pipes_vs_kaldi "$here/../augment/pipes_vs_kaldi.sh" "$TSRIR_BIN" 1000
  run datadir_speed "$here/datadir_speed.sh"
  run band_accuracy "$here/band_accuracy.sh"
fi
if have_rirgen; then run ism_accuracy "$PRA_PYTHON" "$here/ism_accuracy.py" "$TSRIR_BIN" "$RIR_GENERATOR" 20 100
else echo "ism_accuracy: RIR-Generator absent" > "$out_dir/ism_accuracy.txt"; fi
run r3vival_t30 "$here/r3vival_t30.sh"
"$PRA_PYTHON" "$here/summary.py"
