#!/bin/bash
# Regenerates the R3VIVAL diagnosis page from one command: inputs from the data (read in place),
# rir-diagnose into <findings-dir>, the markdown page rendered from its findings.json.
#   docs/results/make_r3vival_page.sh <build-dir> [<page.md> [<findings-dir>]]
# Defaults: docs/results/r3vival.md and docs/results/r3vival (the committed page and outputs).
# R3VIVAL_DIR overrides the data directory (default ../shared/data/rirs/r3vival).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:?usage: $0 <build-dir> [page.md [findings-dir]]}
page=${2:-$root/docs/results/r3vival.md}
out=${3:-$root/docs/results/r3vival}
data=${R3VIVAL_DIR:-$root/../shared/data/rirs/r3vival}
[ -d "$data" ] || { echo "$0: $data not found (the R3VIVAL data of the workplace)" >&2; exit 1; }
[ -x "$build/bin/rir-diagnose" ] || { echo "$0: $build/bin/rir-diagnose not built" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$root/docs/results/make_r3vival_inputs.sh" "$data" "$tmp/in" >&2
"$build/bin/rir-diagnose" --fs=16000 --model=gas --seed=1 --num-threads=2 \
    "$tmp/in/rooms.txt" "$tmp/in/rir.scp" "$tmp/out" >&2
# rir-diagnose writes into a directory of its own; its three files then replace the ones in
# <findings-dir> (the committed findings.json and extended_models, the uncommitted report.html).
mkdir -p "$out"
for f in findings.json extended_models report.html; do cp "$tmp/out/$f" "$out/$f.tmp.$$" && mv "$out/$f.tmp.$$" "$out/$f"; done
python3 "$root/docs/results/render_r3vival_page.py" "$out/findings.json" "$page"
echo "$0: wrote $page and $out/" >&2
