#!/usr/bin/env bash
# The LibriSpeech language models and lexicon (openslr resource 11) into <dir>, each file skipped
# when already complete (a .<file>.complete marker is written after a successful download), and the
# links Kaldi's LibriSpeech scripts expect: lm_tgsmall (3-gram pruned 3e-7), lm_tgmed (pruned
# 1e-7), lm_tglarge (3-gram), lm_fglarge (4-gram), as egs/librispeech/s5/local/download_lm.sh.
set -euo pipefail
help_message="Usage: $0 <base-url> <dir>   e.g.: $0 www.openslr.org/resources/11 exp/kaldi/lm"
. "$(dirname "$0")/../parse_options.sh"
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
url=$1; dir=$2
mkdir -p "$dir"
for f in 3-gram.arpa.gz 3-gram.pruned.1e-7.arpa.gz 3-gram.pruned.3e-7.arpa.gz 4-gram.arpa.gz \
         librispeech-vocab.txt librispeech-lexicon.txt librispeech-lm-norm.txt.gz; do
  [ -f "$dir/.$f.complete" ] && continue
  echo "$0: downloading $url/$f" >&2
  wget --no-verbose --tries=5 -O "$dir/$f.part" "$url/$f" || { echo "$0: download of $url/$f failed" >&2; exit 1; }
  mv "$dir/$f.part" "$dir/$f"
  touch "$dir/.$f.complete"
done
ln -sf 3-gram.pruned.1e-7.arpa.gz "$dir/lm_tgmed.arpa.gz"
ln -sf 3-gram.pruned.3e-7.arpa.gz "$dir/lm_tgsmall.arpa.gz"
ln -sf 3-gram.arpa.gz "$dir/lm_tglarge.arpa.gz"
ln -sf 4-gram.arpa.gz "$dir/lm_fglarge.arpa.gz"
