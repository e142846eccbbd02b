# Sourced by run.sh and the local/ scripts: puts the toolkit's programs (and Kaldi's, when
# KALDI_ROOT is set) on PATH.
#   TSRIR_BIN   directories holding the tsrir programs, colon-separated (default: $BUILD_DIR/bin,
#               BUILD_DIR defaulting to <repo>/build as in utils/run_demo.sh)
#   KALDI_ROOT  a compiled Kaldi checkout: adds its utils/ (run.pl, queue.pl, slurm.pl,
#               validate_data_dir.sh), OpenFst and src/*bin as Kaldi's own path.sh does
tsrir_recipe_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
tsrir_root=$(cd "$tsrir_recipe_dir/../.." && pwd)
TSRIR_BIN=${TSRIR_BIN:-${BUILD_DIR:-$tsrir_root/build}/bin}
export TSRIR_BIN
export PATH=$TSRIR_BIN:$tsrir_recipe_dir/local:$PATH
if [ -n "${KALDI_ROOT:-}" ]; then
  if [ ! -f "$KALDI_ROOT/tools/config/common_path.sh" ]; then
    echo "path.sh: KALDI_ROOT=$KALDI_ROOT is not a Kaldi checkout (no tools/config/common_path.sh)" >&2
    return 1 2>/dev/null || exit 1
  fi
  export PATH=$KALDI_ROOT/egs/wsj/s5/utils:$KALDI_ROOT/tools/openfst/bin:$PATH
  # shellcheck disable=SC1091
  . "$KALDI_ROOT/tools/config/common_path.sh"
  # Kaldi's wav-reverberate must not shadow ours in the pipes we write: reverberate-data writes
  # the absolute path of tsrir's wav-reverberate, so the order here does not matter for them.
fi
# Kaldi's tables are sorted in the C locale (utils/validate_data_dir.sh checks it).
export LC_ALL=C
