#!/usr/bin/env bash
# The full (non-demo) path of run.sh on miniature corpora laid out exactly like the real ones: a
# LibriSpeech tree (4 parts, FLAC + trans.txt + SPEAKERS.TXT) and a BUT ReverbDB tree (3 rooms, one
# of them the staircase; env/spk/mic metadata; RIR/ and silence/ recordings), all generated here
# (tones, rir-simulate RIRs, sox noise), so no download and no ../shared/data is needed. Checks the
# glue the demo does not exercise: corpora found in place (no download), LibriSpeech preparation
# and the train-clean-100 + 360 union, BUT preparation (staircase dropped), the split, stages 2-7,
# stage 8 skipping without Kaldi, and loud failures on a missing corpus.
# Exit 77 when the GAN programs were not built (TSRIR_WITH_TORCH=OFF).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
recipe=$(cd "$here/../../egs/librispeech_farfield" && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
for p in ts-rirgan-train gas-to-real; do
  [ -x "$TSRIR_BIN/$p" ] || { echo "SKIP: $p not built (TSRIR_WITH_TORCH=OFF)"; exit 77; }
done
export PATH=$TSRIR_BIN:$PATH LC_ALL=C
unset KALDI_ROOT
tmp=$(mktemp -d)
trap '[ -n "${KEEP_TMP:-}" ] || rm -rf "$tmp"' EXIT
c=$tmp/corpora

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else fail "$what"; fi; }

# ---- a miniature LibriSpeech ----
n=0
for spec in test-clean:1089-134686-0000 test-clean:1089-134686-0001 test-clean:121-121726-0000 \
            dev-clean:84-121123-0000 dev-clean:84-121123-0001 \
            train-clean-100:103-1240-0000 train-clean-100:103-1240-0001 train-clean-360:14-208-0000; do
  part=${spec%%:*}; u=${spec#*:}; r=${u%%-*}; ch=${u#*-}; ch=${ch%-*}
  n=$((n + 1))
  mkdir -p "$c/LibriSpeech/$part/$r/$ch"
  sox -n -r 16000 -b 16 -c 1 "$c/LibriSpeech/$part/$r/$ch/$u.flac" synth 1.5 sine $((200 + 40 * n)) gain -10
  echo "$u WORDS NUMBER $n" >>"$c/LibriSpeech/$part/$r/$ch/$r-$ch.trans.txt"
done
printf ';ID|SEX|SUBSET|MINUTES|NAME\n1089 | M | test-clean | 1 | A\n84 | F | dev-clean | 1 | B\n' >"$c/LibriSpeech/SPEAKERS.TXT"

# ---- a miniature BUT ReverbDB: 3 rooms x 3 speaker positions x 4 microphones (the EQ fit needs
# >= 14 training RIRs) ----
but=$c/BUT_ReverbDB/BUT_ReverbDB_rel_19_06_RIR-Only
: >"$tmp/rooms.txt"
for room in VUT_FIT_C236:6.5:4.5:3.0 VUT_FIT_E112:9.0:7.0:3.2 VUT_FIT_L227:4.0:3.0:9.0; do
  IFS=: read -r name W D H <<<"$room"
  mkdir -p "$but/$name"
  printf '$EnvWidth\t%s\n$EnvDepth\t%s\n$EnvHeight\t%s\n' "$W" "$D" "$H" >"$but/$name/env_meta.txt"
  for s in 1 2 3; do
    sd=$but/$name/MicID01/SpkID0${s}_20190503_S
    mkdir -p "$sd"
    printf '$EnvSpk1Width\t%s\n$EnvSpk1Depth\t1.0\n$EnvSpk1Height\t1.5\n' "$s.0" >"$sd/spk_meta.txt"
    for m in 1 2 3 4; do
      md=$sd/0$m
      mkdir -p "$md/RIR" "$md/silence"
      printf '$EnvMicID\t%s\n$EnvMic%sWidth\t%s\n$EnvMic%sDepth\t2.%s\n$EnvMic%sHeight\t1.2\n' "$m" "$m" "3.$m" "$m" "$m" "$m" >"$md/mic_meta.txt"
      echo "$name-$s-$m room=$W,$D,$H src=$s.0,1.0,1.5 mic=3.$m,2.$m,1.2 t60=0.$((4 + m)) room-id=$name" >>"$tmp/rooms.txt"
      sox -n -r 16000 -b 16 -c 1 "$md/silence/silence_16kHz_60sec.v00.wav" synth 3 pinknoise gain -40
    done
  done
done
rir-simulate --fs=16000 "$tmp/rooms.txt" "$tmp/sim" 2>/dev/null || { echo "FAIL: rir-simulate for the fabricated BUT tree" >&2; exit 1; }
while read -r id _; do
  name=${id%-*-*}; rest=${id#"$name"-}; s=${rest%-*}; m=${rest#*-}
  cp "$tmp/sim/$id.wav" "$but/$name/MicID01/SpkID0${s}_20190503_S/0$m/RIR/IR_sweep_15s_45Hzto22kHz_FS16kHz.v00.wav"
done <"$tmp/rooms.txt"

run() { "$recipe/run.sh" --corpus-dir "$c" --data "$tmp/data" --exp "$tmp/exp" --results "$tmp/RESULTS.md" \
  --gan-steps 3 --gan-width 4 --gan-batch-size 4 --gan-num-threads 1 --nj 2 --num-threads 1 "$@"; }

run --stop-stage 8 >"$tmp/out" 2>"$tmp/err"
rc=$?
[ $rc -eq 0 ] || { tail -n 30 "$tmp/err" >&2; echo "FAIL: run.sh (full path, stages 0-8) exited with $rc" >&2; exit 1; }
echo "ok: run.sh stages 0-8 on the miniature corpora"
for part in train-clean-100 train-clean-360 dev-clean test-clean; do
  check "stage 0: $part found in place, not downloaded" grep -q "stage 0: .*LibriSpeech/$part present, not downloading" "$tmp/err"
done
check "stage 0: BUT ReverbDB found in place" grep -q 'stage 0: BUT ReverbDB present' "$tmp/err"
check "stage 1: LibriSpeech dirs with every utterance (3 test, 2 dev, 2 + 1 train)" \
  test "$(wc -l <"$tmp/data/test_clean/wav.scp") $(wc -l <"$tmp/data/dev_clean/wav.scp") $(wc -l <"$tmp/data/train_clean_460/wav.scp")" = "3 2 3"
check "stage 1: train_clean_460 is a valid union of train-clean-100 and 360" \
  bash -c "validate-data-dir --no-feats '$tmp/data/train_clean_460' 2>/dev/null && grep -q '^14-208-0000 ' '$tmp/data/train_clean_460/wav.scp' && grep -q '^103-1240-0001 ' '$tmp/data/train_clean_460/wav.scp'"
check "stage 1: BUT staircase dropped, 24 of 36 RIRs kept" \
  grep -qx 'found=36 staircase_dropped=12 outside_room_dropped=0 repeats_dropped=0 kept=24' "$tmp/data/local/but/counts.txt"
# run.sh splits by source position (--group-fields "3 4 5 6 7 8": room, speaker position x y z,
# ...): whole groups, so the sizes only approximate the scaled 15/4/5; what must hold is that every
# RIR is in exactly one part and no group has RIRs in two parts.
check "stage 1: 24 RIRs split by source position (groups=fields 3 4 5 6 7 8)" \
  grep -q '^total=24 .*groups=fields 3 4 5 6 7 8' "$tmp/data/rirs/split/split.txt"
check "stage 1: every RIR in exactly one part, no source position in two parts" \
  awk 'FNR == 1 { part = FILENAME } part ~ /meta.txt$/ { key[$1] = $3 " " $4 " " $5 " " $6 " " $7 " " $8; next }
       { n++; if ($1 in seen) bad = 1; seen[$1] = 1; k = key[$1]; if (k == "") bad = 1
         if (k in owner && owner[k] != part) bad = 1; owner[k] = part }
       END { exit bad || n != 24 }' "$tmp/data/rirs/real_all/meta.txt" \
      "$tmp/data/rirs/split/train.ids" "$tmp/data/rirs/split/dev.ids" "$tmp/data/rirs/split/test.ids"
check "stage 1: no staircase RIR in any list" bash -c "! grep -q VUT_FIT_L227 '$tmp'/data/rirs/real_*/rir_list"
check "stage 2: GAS metadata from BUT (room VUT_FIT_E112 is 9 x 7 x 3.2 m)" \
  grep -q '^VUT_FIT_E112-SpkID01_20190503_S-01 room=9,7,3.2 ' "$tmp/data/rirs/gas_all/room_list"
check "stage 6: Table 1 printed" grep -q '^G(GAS)+EQ ' "$tmp/out"
for d in train_clean_460_rvb_gas_gsr_eq train_clean_460_rvb_real dev_clean_rvb_real test_clean_rvb_real; do
  check "stage 7: $d valid, pipes in wav.scp (Kaldi's way)" \
    bash -c "validate-data-dir --no-feats '$tmp/data/$d' 2>/dev/null && awk '\$NF != \"|\" {bad = 1} END {exit bad}' '$tmp/data/$d/wav.scp'"
done
check "stage 7: far-field pipes decode (the first test utterance)" \
  bash -c "rx=\$(awk 'NR == 1 {\$1 = \"\"; print}' '$tmp/data/test_clean_rvb_real/wav.scp'); bash -c \"\${rx% |}\" 2>/dev/null | sox -t wav - -n stat 2>&1 | grep -q 'Length (seconds): *1.500000'"
check "stage 8: skipped with a message without KALDI_ROOT" grep -q 'stage 8: KALDI_ROOT is not set: skipping' "$tmp/err"

# Missing corpora fail loudly, naming what is missing.
run --stage 1 --stop-stage 1 --librispeech-dir "$tmp/nowhere/LibriSpeech" >/dev/null 2>"$tmp/err_missing"
check "a missing LibriSpeech part stops stage 1 with its name" \
  bash -c "test $? -ne 0 && grep -q 'nowhere/LibriSpeech/train-clean-100' '$tmp/err_missing'"

if [ "$failures" -gt 0 ]; then echo "$failures check(s) failed" >&2; exit 1; fi
echo "all full-path checks passed"
