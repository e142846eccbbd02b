#!/usr/bin/env bash
# Golden outputs of rir-metrics (iso and irstats, table with bands, JSON, Table 1 against a
# reference set): the text a refactoring must keep (tests/common/golden/compare.py).
# Usage: golden_test.sh <bin-dir>
source "$(dirname "${BASH_SOURCE[0]}")/../common/golden/golden.sh" "$1" "$(dirname "${BASH_SOURCE[0]}")/golden"

"$bin/rir-metrics" --bands real/rir.scp sim/rir.scp > "$out/iso_bands.txt" 2>/dev/null
"$bin/rir-metrics" --format=json --lundeby=false --clarity-ms=80 real/rir.scp > "$out/iso_raw.json" 2>/dev/null
"$bin/rir-metrics" --definition=irstats --bands --num-threads=2 sim/rir.scp > "$out/irstats_bands.txt" 2>/dev/null
"$bin/rir-metrics" --definition=irstats --format=json sim/rir.scp > "$out/irstats.json" 2>/dev/null
"$bin/rir-metrics" --reference=real/rir.scp sim/rir.scp --output="$out/table1_iso.txt" 2>/dev/null
"$bin/rir-metrics" --definition=irstats --reference=real/rir.scp sim/rir.scp > "$out/table1_irstats.txt" 2>/dev/null
golden_finish
