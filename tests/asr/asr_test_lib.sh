# Shared by the downstream experiment's small CI versions (asr_sensitivity_test.sh,
# asr_control_test.sh): the programs on PATH, the held-out RIR split and the reverberation step.
# Sourced after `tmp` (a scratch dir) and `repo` are set. Exit 77 (skip): espeak-ng missing.
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
export PATH=$TSRIR_BIN:$PATH LC_ALL=C
command -v espeak-ng >/dev/null || { echo "SKIP: espeak-ng is not installed (utils/bootstrap.sh installs it)"; exit 77; }

# require_programs <name>...: each must be built.
require_programs() {
  local p
  for p in "$@"; do [ -x "$TSRIR_BIN/$p" ] || { echo "FAIL: $TSRIR_BIN/$p is not built" >&2; exit 1; }; done
}

# split_test_rirs <conditions> <shared-data-dir>: $tmp/train_rir_list and $tmp/test_rir_list.
# Measured R3VIVAL RIRs of the given conditions (e.g. "000 050"), source positions sorted by name,
# every third position held out for the test in every condition (no position on both sides);
# without ../shared/data, RIRs of random rooms from the independent generator of tests/diagnose
# (make_test_rirs: no code of the simulator under study).
split_test_rirs() {
  local conditions=$1 r3v=$2/rirs/r3vival c
  if ls "$r3v"/RLRVarAcLab_Absorptive_000_*_ch7.wav >/dev/null 2>&1; then
    for c in $conditions; do ls "$r3v"/RLRVarAcLab_Absorptive_${c}_*_ch7.wav | sort; done |
      awk -v d="$tmp" '{ id = $0; sub(/.*Absorptive_/, "", id); sub(/_R1_.*/, "", id); pos = id; sub(/^[0-9]*_/, "", pos)
        if (!(pos in k)) k[pos] = n++
        print "--rir-id " id " --room-id r3vival " $0 > (d "/" (k[pos] % 3 == 2 ? "test" : "train") "_rir_list") }'
    echo "RIRs: measured R3VIVAL condition(s) $conditions from $r3v: $(wc -l <"$tmp/train_rir_list") training, $(wc -l <"$tmp/test_rir_list") held out (by source position)"
  else
    : "${TSRIR_TEST_RIRS:?TSRIR_TEST_RIRS must name the make_test_rirs helper}"
    "$TSRIR_TEST_RIRS" "$tmp/rirs_train" 24 11 && "$TSRIR_TEST_RIRS" "$tmp/rirs_test" 12 12 ||
      { echo "FAIL: make_test_rirs" >&2; exit 1; }
    cp "$tmp/rirs_train/rir_list" "$tmp/train_rir_list"; cp "$tmp/rirs_test/rir_list" "$tmp/test_rir_list"
    echo "RIRs: $r3v absent: 24 training and 12 test RIRs of random rooms from the independent generator (make_test_rirs)"
  fi
}

# reverb <rir-list> <in-data-dir> <out-data-dir> [seed]: every utterance convolved with a random RIR
# of the list, no noise (reverberate-data, seeded: 3 unless given).
reverb() {
  reverberate-data --rir-set-parameters "1.0, $1" --speech-rvb-probability 1 \
    --pointsource-noise-addition-probability 0 --isotropic-noise-addition-probability 0 --random-seed "${4:-3}" \
    --num-threads 2 --write-wavs "$tmp/wav/$(basename "$3")" "$2" "$3" 2>"$tmp/rvb.log" ||
    { tail "$tmp/rvb.log" >&2; echo "FAIL: reverberate-data $2" >&2; exit 1; }
}
