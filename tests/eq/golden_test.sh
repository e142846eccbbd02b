#!/usr/bin/env bash
# Golden outputs of rir-eq (fit: both models; gains; apply; fit + apply in one run): the bytes a
# refactoring must keep (tests/common/golden/compare.py). Usage: golden_test.sh <bin-dir>
source "$(dirname "${BASH_SOURCE[0]}")/../common/golden/golden.sh" "$1" "$(dirname "${BASH_SOURCE[0]}")/golden"

"$bin/rir-eq" fit real/rir.scp "$out/indep.model" 2>/dev/null
"$bin/rir-eq" fit --model=gmm --components=2 --covariance=diag --seed=3 real/rir.scp "$out/gmm.model" 2>/dev/null
"$bin/rir-eq" gains --gain-method=smooth sim/rir.scp "$out/sim_gains.txt" 2>/dev/null
"$bin/rir-eq" apply --seed=7 --num-threads=2 "$out/indep.model" sim/rir.scp "$out/sim_eq" 2>/dev/null
"$bin/rir-eq" --real=real/rir.scp --model=gmm --components=2 --seed=5 --format=float \
  --model-out="$out/oneshot.model" sim/rir.scp "$out/sim_eq_float" 2>/dev/null
golden_finish
