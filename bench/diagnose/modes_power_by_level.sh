#!/bin/bash
# room_modes detection at fixed PHYSICAL strengths, for one or two builds of diagnose_probe side by
# side: the hidden modes (tests' independent generator, decaying 2x the room's low-band T60) at
# level G dB re the generator's nominal modal level, 48 RIRs per set (24 decide, 24 judged).
# Power sweeps in units of a detector's own threshold (power_sweep.sh) cannot compare two
# statistics; this can: the same sets, the same hidden modes, each build's own decision.
#   bench/diagnose/modes_power_by_level.sh "<label>=<build-dir> [<label>=<build-dir>]" ["G list"] [seeds] [null sets]
# e.g. (a build of an older commit in /work/old/build):
#   bench/diagnose/modes_power_by_level.sh "before=/work/old/build now=build" "-12 -9 -6 -3" 15 15
# Prints, per build, the fraction of sets reporting room_modes at each level, the mean statistic,
# and the fraction of null sets (nothing hidden) reporting it. JOBS=N probes at a time.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
jobs=${JOBS:-$("$root/utils/cores")}
builds=${1:?usage: $0 "<label>=<build-dir> ..." ["G list"] [seeds] [null sets]}
levels=${2:--12 -9 -6 -3}
seeds=${3:-15}
nulls=${4:-15}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $("$root/utils/cores") cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u '+%F %H:%M') UTC; levels $levels dB; $seeds sets per level (seeds 601..), $nulls null sets (seeds 501..)"
: > "$tmp/jobs"
for b in $builds; do
  label=${b%%=*}
  dir=${b#*=}
  [ -x "$dir/bin/diagnose_probe" ] || { echo "$0: $dir/bin/diagnose_probe not built (ninja -C $dir diagnose_probe)" >&2; exit 1; }
  for s in $(seq 1 "$nulls"); do echo "$label $dir null $((500 + s))" >> "$tmp/jobs"; done
  for g in $levels; do
    for s in $(seq 1 "$seeds"); do echo "$label $dir $g $((600 + s))" >> "$tmp/jobs"; done
  done
done
run_one() {  # <label> <build> <level|null> <seed>
  local fix=() out
  [ "$3" = null ] || fix=(--effects=room_modes "--fix=mode_gain_db=$3,mode_decay_factor=2")
  out=$("$2/bin/diagnose_probe" --count=48 --seed="$4" "${fix[@]}" 2>/dev/null) || { echo "$1 $3 seed $4 failed" >&2; return 0; }
  local detected stat
  detected=$(grep '^seed' <<<"$out" | grep -cw room_modes || true)
  stat=$(awk '$1 == "stat" && $2 == "room_modes" { print $4 }' <<<"$out")
  echo "$1 $3 $4 $detected $stat" > "$tmp/res.$1.$3.$4"
}
export -f run_one
export tmp
xargs -P "$jobs" -L 1 bash -c 'run_one "$@"' _ < "$tmp/jobs"
cat "$tmp"/res.* > "$tmp/all"
echo
header="| build | null sets reporting room_modes |"
rule="|---|---|"
for g in $levels; do header="$header G = $g dB: detected (mean statistic) |"; rule="$rule---|"; done
echo "$header"
echo "$rule"
for b in $builds; do
  label=${b%%=*}
  row="| $label | $(awk -v l="$label" '$1 == l && $2 == "null" { n++; c += $4 } END { printf "%d/%d", c, n }' "$tmp/all") |"
  for g in $levels; do
    row="$row $(awk -v l="$label" -v g="$g" '$1 == l && $2 == g { n++; c += $4; s += $5 } END { printf "%d/%d (%.2f dB)", c, n, n ? s / n : 0 }' "$tmp/all") |"
  done
  echo "$row"
done
