# The golden-output tests' frame, sourced by tests/<area>/golden_test.sh:
#   source tests/common/golden/golden.sh <bin-dir> <golden-dir>
# makes the inputs (make_inputs.py) in $in, runs nothing itself, and gives the area's script
# $bin, $in (the working directory: lists name inputs relative to it), $out (where every output
# goes), run_pipes (materialises a wav.scp's pipes) and golden_finish (compares $out with
# <golden-dir>, see compare.py). TSRIR_GOLDEN_UPDATE=1 rewrites <golden-dir> from this run (only
# with the build whose outputs are to be kept).
set -euo pipefail
golden_common=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
bin=$(cd "$1" && pwd -P)
golden_dir=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
work=$(cd "$(mktemp -d "${TMPDIR:-/tmp}/tsrir_golden.XXXXXX")" && pwd -P)
trap 'rm -rf "$work"' EXIT
in=$work/in
out=$work/out
mkdir -p "$out"
python3 "$golden_common/make_inputs.py" "$in"
cd "$in"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

# Runs every pipe of <data-dir>/wav.scp from $in (as a Kaldi recipe runs them) into <dir>/<id>.wav.
run_pipes() {
  local data=$1 dir=$2 id rx
  mkdir -p "$dir"
  while read -r -u 3 id rx; do
    bash -c "${rx% |}" > "$dir/$id.wav" < /dev/null 2>/dev/null
  done 3< "$data/wav.scp"
}

golden_finish() {
  local update=()
  [ "${TSRIR_GOLDEN_UPDATE:-0}" = 1 ] && update=(--update)
  python3 "$golden_common/compare.py" --expected "$golden_dir" --actual "$out" \
    --replace "$work=@WORK@" --replace "$bin=@BIN@" "${update[@]}"
}
