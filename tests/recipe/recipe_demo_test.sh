#!/usr/bin/env bash
# Runs the README's main job in its reduced form, `run.sh --demo --demo-size tiny`, into a
# temporary directory, and checks what the issue asks of it: every stage reports progress, Table 1
# is printed with every RIR set, the far-field data dirs pass the data-dir validator (and Kaldi's
# own, when KALDI_ROOT is set), their audio exists and keeps each utterance's length, and a second
# run skips the completed work. Exit 77 (skipped) when the GAN programs were not built
# (TSRIR_WITH_TORCH=OFF): the demo needs them.
# Env: TSRIR_BIN = the directory of the built programs (set by CTest).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
recipe=$(cd "$here/../../egs/librispeech_farfield" && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
for p in rir-room-list rir-simulate rir-eq rir-metrics reverberate-data wav-reverberate validate-data-dir; do
  [ -x "$TSRIR_BIN/$p" ] || { echo "FAIL: $TSRIR_BIN/$p is not built" >&2; exit 1; }
done
for p in ts-rirgan-train gas-to-real; do
  [ -x "$TSRIR_BIN/$p" ] || { echo "SKIP: $p not built (TSRIR_WITH_TORCH=OFF); the demo needs it"; exit 77; }
done
export PATH=$TSRIR_BIN:$PATH LC_ALL=C
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
w=$tmp/demo

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else fail "$what"; fi; }

start=$SECONDS
"$recipe/run.sh" --demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md" \
  >"$tmp/out1" 2>"$tmp/err1"
rc=$?
first_s=$((SECONDS - start))
if [ $rc -ne 0 ]; then
  tail -n 40 "$tmp/err1" >&2
  echo "FAIL: run.sh --demo --demo-size tiny exited with $rc" >&2
  exit 1
fi
echo "ok: the tiny demo ran in $first_s s"

for s in 0 1 2 3 4 5 6 7; do
  check "stage $s printed its progress and completion" grep -q "^run.sh: stage $s done" "$tmp/err1"
done
# Table 1 on stdout: the reference row and one row per RIR set, each with its 4 parameters.
for set in real 'GAS' 'GAS+EQ' 'G(GAS)' 'G(GAS+EQ)' 'G(GAS)+EQ'; do
  check "Table 1 has the row $set" \
    awk -v s="$set" '$1 == s && NF >= 6 {found = 1} END {exit !found}' "$tmp/out1"
done
check "Table 1 is in RESULTS.md with the data sources of the run" \
  bash -c "grep -q 'Table 1' '$w/RESULTS.md' && grep -q 'G(GAS)+EQ' '$w/RESULTS.md' && grep -q '^- rirs ' '$w/RESULTS.md'"

data=$w/data
dirs="train_clean_rvb_real train_clean_rvb_gas train_clean_rvb_gas_eq train_clean_rvb_gas_gsr
      train_clean_rvb_gas_eq_gsr train_clean_rvb_gas_gsr_eq dev_clean_rvb_real test_clean_rvb_real"
for d in $dirs; do
  check "$d is a valid Kaldi data dir (validate-data-dir --no-feats)" validate-data-dir --no-feats "$data/$d" 2>/dev/null
  if [ -n "${KALDI_ROOT:-}" ]; then
    check "$d passes Kaldi's utils/validate_data_dir.sh --no-feats" \
      bash -c "cd '$KALDI_ROOT/egs/wsj/s5' && utils/validate_data_dir.sh --no-feats '$data/$d'"
  fi
done
# Every far-field recording: a 16-bit wav of the clean utterance's length (shift-output keeps it).
while read -r id wav; do
  clean=$(awk -v u="$id" '$1 == u {$1 = ""; print}' "$data/test_clean/wav.scp")
  n_clean=$(bash -c "sox ${clean% |} -n stat" 2>&1 | awk '/Samples read/ {print $3}')
  n_far=$(sox "$wav" -n stat 2>&1 | awk '/Samples read/ {print $3}')
  check "test_clean_rvb_real/$id: audio exists, same length as the clean utterance ($n_far vs $n_clean samples)" \
    test -n "$n_far" -a "$n_far" = "$n_clean"
  rms=$(sox "$wav" -n stat 2>&1 | awk '/RMS +amplitude/ {print $3}')
  check "test_clean_rvb_real/$id: not silent (RMS $rms)" awk -v r="$rms" 'BEGIN {exit !(r > 0.001)}'
done <"$data/test_clean_rvb_real/wav.scp"
check "the test set uses only real test RIRs" \
  bash -c "test \$(wc -l < '$data/rirs/real_test/rir.scp') -gt 0 && ! grep -q gas '$data/test_clean_rvb_real/wav.scp'"

# A tampered copy must be rejected: the validator used above can fail.
cp -r "$data/test_clean_rvb_real" "$tmp/tampered"
sort -r "$tmp/tampered/utt2spk" -o "$tmp/tampered/utt2spk"
check "the validator rejects a tampered copy (utt2spk unsorted)" \
  bash -c "! validate-data-dir --no-feats '$tmp/tampered' 2>/dev/null"

# A user's own files beside the recipe's outputs survive every later run (issue 14: a stage creates
# or replaces only what it writes): table 1's dir (redone each run), the GAN model dir (retrained
# below), a --write-wavs dir (emptied by the pipe-mode run below), the GAS set's dir.
sentinels="$w/exp/table1/MY_NOTES $w/exp/tsrirgan/MY_NOTES $data/wav/test_clean_rvb_real/MY_NOTES $data/rirs/gas_all/MY_NOTES"
for f in $sentinels; do echo "mine: $f" >"$f"; done

# Idempotence: a second run skips every completed step.
start=$SECONDS
"$recipe/run.sh" --demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md" \
  >"$tmp/out2" 2>"$tmp/err2"
rc=$?
second_s=$((SECONDS - start))
check "a second run succeeds" test $rc -eq 0
check "a second run skips the GAN training" grep -q 'stage 4: TS-RIRGAN already trained' "$tmp/err2"
check "a second run skips the simulation" grep -q 'stage 2: GAS RIRs already simulated' "$tmp/err2"
check "a second run is faster ($second_s s vs $first_s s)" test "$second_s" -lt "$first_s" -o "$second_s" -le 30
check "a second run prints the same Table 1" diff -q "$tmp/out1" "$tmp/out2"

# A changed setting redoes exactly what depends on it: another GAN (--gan-steps) retrains stage 4
# and remakes the translated sets of stage 5, but not GAS+EQ, which does not depend on the GAN.
"$recipe/run.sh" --demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md" \
  --stage 4 --stop-stage 5 --gan-steps 7 >/dev/null 2>"$tmp/err_gan"
check "a new --gan-steps retrains the GAN" bash -c "! grep -q 'TS-RIRGAN already trained' '$tmp/err_gan' && grep -q '^run.sh: stage 4 done' '$tmp/err_gan'"
check "... and remakes G(GAS), G(GAS+EQ), G(GAS)+EQ for both splits" \
  test "$(grep -c 'stage 5:   G(GAS\(+EQ\)\?)\(+EQ\)\? (\(train\|test\)):' "$tmp/err_gan")" -eq 6
check "... but not GAS+EQ" bash -c "! grep -q 'stage 5:   GAS+EQ' '$tmp/err_gan'"

# Kaldi's way: wav.scp pipes instead of wavs. The same seed must give the same audio, so each pipe,
# run through bash as Kaldi runs it, must reproduce the wav written before, sample for sample.
cp -r "$data/wav/test_clean_rvb_real" "$tmp/wavs_mode"
"$recipe/run.sh" --demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md" \
  --stage 7 --stop-stage 7 --write-wavs false >/dev/null 2>"$tmp/err_pipes"
check "stage 7 with --write-wavs false succeeds" test $? -eq 0
check "pipe mode: every wav.scp entry is a wav-reverberate pipe" \
  awk '!($NF == "|" && /wav-reverberate/) {bad = 1} END {exit bad || NR == 0}' "$data/test_clean_rvb_real/wav.scp"
while read -r id rx; do
  a=$(bash -c "${rx% |}" 2>/dev/null | sox -t wav - -t raw - | md5sum)
  b=$(sox "$tmp/wavs_mode/$id.wav" -t raw - | md5sum)
  check "pipe mode: $id's pipe reproduces its wav sample for sample" test "$a" = "$b"
done <"$data/test_clean_rvb_real/wav.scp"
check "pipe mode: a valid data dir" validate-data-dir --no-feats "$data/test_clean_rvb_real" 2>/dev/null

for f in $sentinels; do
  check "a user's file survives the re-runs: ${f#$w/}" bash -c "test \"\$(cat '$f')\" = 'mine: $f'"
done

# Missing inputs fail loudly: stage 3 without the real RIR lists.
rm "$data/rirs/real_train/rir_list"
"$recipe/run.sh" --demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md" \
  --stage 3 --stop-stage 3 >/dev/null 2>"$tmp/err3"
rc=$?
check "a missing input stops the stage with an error naming it" \
  bash -c "test $rc -ne 0 && grep -q 'missing input .*real_train/rir_list' '$tmp/err3'"

if [ "$failures" -gt 0 ]; then echo "$failures check(s) failed" >&2; exit 1; fi
echo "all demo checks passed"
