#!/usr/bin/env bash
# Validates a Kaldi data directory without features: always with the toolkit's validate-data-dir,
# and also with Kaldi's own utils/validate_data_dir.sh --no-feats when KALDI_ROOT is set. Both
# must accept it.
set -euo pipefail
help_message="Usage: $0 <data-dir>"
. ./local/parse_options.sh
[ $# -eq 1 ] || { echo "$help_message" >&2; exit 1; }
dir=$1
command -v validate-data-dir >/dev/null || { echo "$0: validate-data-dir not on PATH (build the toolkit)" >&2; exit 1; }
[ -d "$dir" ] || { echo "$0: no such data dir $dir" >&2; exit 1; }
abs=$(readlink -f "$dir")
validate-data-dir --no-feats "$abs" 2>/dev/null || { validate-data-dir --no-feats "$abs" || true; exit 1; }
if [ -n "${KALDI_ROOT:-}" ]; then
  v=$KALDI_ROOT/egs/wsj/s5/utils/validate_data_dir.sh
  [ -x "$v" ] || { echo "$0: KALDI_ROOT is set but $v is missing" >&2; exit 1; }
  # Kaldi's validator calls utils/*.pl relative to the current directory.
  (cd "$KALDI_ROOT/egs/wsj/s5" && utils/validate_data_dir.sh --no-feats "$abs") >&2 ||
    { echo "$0: Kaldi's validate_data_dir.sh rejects $dir" >&2; exit 1; }
fi
