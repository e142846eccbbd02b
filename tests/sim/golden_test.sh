#!/usr/bin/env bash
# Golden outputs of rir-simulate (int16 and float, two models) and rir-room-list (a room table,
# two absorption draws): the bytes a refactoring must keep (tests/common/golden/compare.py).
# Usage: golden_test.sh <bin-dir>
source "$(dirname "${BASH_SOURCE[0]}")/../common/golden/golden.sh" "$1" "$(dirname "${BASH_SOURCE[0]}")/golden"

"$bin/rir-simulate" --length=0.2 rooms.txt "$out/gas" 2>/dev/null
"$bin/rir-simulate" --length=0.2 --sample-rate=8000 --model=gas+air --seed=3 --num-threads=2 --format=float \
  rooms.txt "$out/air_float" 2>/dev/null
"$bin/rir-room-list" room_table.txt "$out/rooms_surface.txt" 2>/dev/null
"$bin/rir-room-list" --absorption-draw=surface-band --random-seed=5 room_table.txt - > "$out/rooms_bands.txt" 2>/dev/null
golden_finish
