#!/usr/bin/env bash
# Downloads <url> into <dir> and unpacks it there, skipped when <dir>/.<name>.complete exists
# (written only after a successful unpack, so an interrupted run resumes: wget -c continues a
# partial archive). --remove-archive deletes the archive after unpacking.
#   e.g. local/download_and_untar.sh corpora https://www.openslr.org/resources/12/dev-clean.tar.gz
set -euo pipefail
remove_archive=false
help_message="Usage: $0 [--remove-archive true|false] <dir> <url>"
. ./local/parse_options.sh
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
dir=$1; url=$2
name=$(basename "$url")
mkdir -p "$dir"
if [ -f "$dir/.$name.complete" ]; then
  echo "$0: $name already unpacked in $dir (remove $dir/.$name.complete to redo)" >&2
  exit 0
fi
if command -v wget >/dev/null; then
  wget --no-verbose --continue --tries=5 --directory-prefix="$dir" "$url" ||
    { echo "$0: download of $url failed" >&2; exit 1; }
elif command -v curl >/dev/null; then
  curl --fail --location --retry 5 --continue-at - --output "$dir/$name" "$url" ||
    { echo "$0: download of $url failed" >&2; exit 1; }
else
  echo "$0: neither wget nor curl is installed" >&2
  exit 1
fi
echo "$0: unpacking $dir/$name" >&2
tar -xzf "$dir/$name" -C "$dir" || { echo "$0: $dir/$name is not a valid tar.gz archive" >&2; exit 1; }
touch "$dir/.$name.complete"
[ "$remove_archive" = true ] && rm -f "$dir/$name"
exit 0
