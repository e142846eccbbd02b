#!/usr/bin/env bash
# The real RIRs and noises of BUT ReverbDB (BUT_ReverbDB_rel_19_06_RIR-Only, Szoke et al. 2019) as
# the recipe's tables. The release's layout and metadata (tab-separated "$Key<TAB>value" lines):
#   <Room>/env_meta.txt                         $EnvWidth $EnvDepth $EnvHeight (m)
#   <Room>/MicID01/<SpkID..>/spk_meta.txt       $EnvSpk1Width $EnvSpk1Depth $EnvSpk1Height
#   <Room>/MicID01/<SpkID..>/<NN>/mic_meta.txt  $EnvMicID = i; $EnvMic<i>Width/Depth/Height
#   <Room>/MicID01/<SpkID..>/<NN>/RIR/*.wav     the RIR (16 kHz); silence/*.wav: room noise
# As the paper (TS-RIR sec. 3.3), the staircase (--skip-rooms, VUT_FIT_L227) and repeated RIRs are
# dropped; a repeat is a second RIR of the same room with the same source and microphone positions
# (to the cm), the first in sorted path order is kept. RIRs whose source or microphone lies outside
# the documented room cannot be simulated (stage 2) and are dropped too; every count is logged.
# Writes <out>/meta.txt (<rir-id> <room-id> Lx Ly Lz sx sy sz mx my mz, x = width, y = depth,
# z = height), rir.scp, rir_list and noise.scp (the silence recordings of the kept positions).
set -euo pipefail
skip_rooms=VUT_FIT_L227
help_message="Usage: $0 [--skip-rooms 'ROOM ...'] <BUT_ReverbDB-dir> <out-dir>"
. ./local/parse_options.sh
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
[ -d "$1" ] || { echo "$0: no such directory $1" >&2; exit 1; }
src=$(readlink -f "$1"); out=$2

meta_get() {  # <file> <key>: the value, or an error naming the file
  local v
  [ -f "$1" ] || { echo "$0: missing metadata file $1" >&2; return 1; }
  v=$(awk -F'\t' -v k="$2" '{sub(/\r$/, "")} $1 == k {print $2; exit}' "$1" | tr -d ' ')
  [[ "$v" =~ ^-?[0-9]+(\.[0-9]*)?$ ]] || { echo "$0: $1: no numeric $2 (got '$v')" >&2; return 1; }
  echo "$v"
}

tmp=$out.tmp.$$
rm -rf "$tmp"; mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT
found=0; skipped=0; outside=0; repeats=0
: >"$tmp/meta.txt"; : >"$tmp/rir.scp"; : >"$tmp/noise.scp"; : >"$tmp/keys"
while read -r env; do
  roomdir=$(dirname "$env"); room=$(basename "$roomdir")
  W=$(meta_get "$env" '$EnvWidth'); D=$(meta_get "$env" '$EnvDepth'); H=$(meta_get "$env" '$EnvHeight')
  for spkdir in "$roomdir"/MicID01/SpkID*; do
    [ -d "$spkdir" ] || continue
    sx=$(meta_get "$spkdir/spk_meta.txt" '$EnvSpk1Width')
    sy=$(meta_get "$spkdir/spk_meta.txt" '$EnvSpk1Depth')
    sz=$(meta_get "$spkdir/spk_meta.txt" '$EnvSpk1Height')
    for micdir in "$spkdir"/[0-9]*; do
      [ -d "$micdir/RIR" ] || continue
      rir=$(find "$micdir/RIR" -maxdepth 1 -name '*.wav' | LC_ALL=C sort | head -n 1)
      [ -n "$rir" ] || continue
      found=$((found + 1))
      if [[ " $skip_rooms " == *" $room "* ]]; then skipped=$((skipped + 1)); continue; fi
      mic=$(meta_get "$micdir/mic_meta.txt" '$EnvMicID' | sed 's/\.0*$//')
      mx=$(meta_get "$micdir/mic_meta.txt" "\$EnvMic${mic}Width")
      my=$(meta_get "$micdir/mic_meta.txt" "\$EnvMic${mic}Depth")
      mz=$(meta_get "$micdir/mic_meta.txt" "\$EnvMic${mic}Height")
      if ! awk -v W="$W" -v D="$D" -v H="$H" -v a="$sx $sy $sz $mx $my $mz" 'BEGIN {
             n = split(a, p, " ")
             for (i = 0; i < 2; i++)
               if (!(p[3*i+1] > 0 && p[3*i+1] < W && p[3*i+2] > 0 && p[3*i+2] < D && p[3*i+3] > 0 && p[3*i+3] < H)) exit 1 }'; then
        outside=$((outside + 1)); continue
      fi
      key=$(awk -v r="$room" -v a="$sx $sy $sz $mx $my $mz" 'BEGIN {split(a, p, " "); s = r; for (i = 1; i <= 6; i++) s = s sprintf(" %.2f", p[i]); print s}')
      if grep -qxF "$key" "$tmp/keys"; then repeats=$((repeats + 1)); continue; fi
      echo "$key" >>"$tmp/keys"
      id=$room-$(basename "$spkdir")-$(basename "$micdir")
      echo "$id $room $W $D $H $sx $sy $sz $mx $my $mz" >>"$tmp/meta.txt"
      echo "$id $rir" >>"$tmp/rir.scp"
      noise=$(find "$micdir/silence" -maxdepth 1 -name '*.wav' 2>/dev/null | LC_ALL=C sort | head -n 1 || true)
      [ -n "$noise" ] && echo "$id-silence $noise" >>"$tmp/noise.scp"
    done
  done
done < <(find "$src" -name env_meta.txt | LC_ALL=C sort)
[ "$found" -gt 0 ] || { echo "$0: no <Room>/MicID01/SpkID*/<NN>/RIR/*.wav under $src" >&2; exit 1; }
[ -s "$tmp/noise.scp" ] || { echo "$0: no silence/*.wav noise recordings under $src" >&2; exit 1; }
for f in meta.txt rir.scp noise.scp; do LC_ALL=C sort -o "$tmp/$f" "$tmp/$f"; done
awk 'NR == FNR {room[$1] = $2; next} {print "--rir-id " $1 " --room-id " room[$1] " " $2}' \
  "$tmp/meta.txt" "$tmp/rir.scp" >"$tmp/rir_list"
rm "$tmp/keys"
kept=$(wc -l <"$tmp/meta.txt")
echo "found=$found staircase_dropped=$skipped outside_room_dropped=$outside repeats_dropped=$repeats kept=$kept" >"$tmp/counts.txt"
echo "$0: $(cat "$tmp/counts.txt") (the paper keeps 1209 of 1891)" >&2
rm -rf "$out"
mv "$tmp" "$out"
trap - EXIT
