#!/usr/bin/env bash
# Tests of the recipe's helper scripts (egs/librispeech_farfield/local) on fabricated inputs whose
# right answers are known by construction: Kaldi's option and job-runner conventions, the seeded
# RIR split, random absorption, the BUT ReverbDB and LibriSpeech preparation, the data-dir
# validator (ours must agree with Kaldi's rules), the WER collector, and the demo corpus's
# stand-ins (what a clone without ../shared/data gets).
# Env: TSRIR_BIN = the directory of the built programs (set by CTest).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
recipe=$(cd "$here/../../egs/librispeech_farfield" && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
export PATH=$TSRIR_BIN:$recipe/local:$PATH LC_ALL=C
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$recipe"

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else fail "$what"; fi; }
# expect_fail <what> <command...>: the command must exit non-zero
expect_fail() { local what=$1; shift; if "$@" >/dev/null 2>&1; then fail "$what (succeeded)"; else echo "ok: $what"; fi; }

# ---- parse_options.sh: Kaldi's conventions ----
cat >"$tmp/opts.sh" <<'EOF'
foo_bar=1
flag=false
help_message="usage: opts"
. ./local/parse_options.sh
echo "$foo_bar $flag $*"
EOF
check "parse_options: --foo-bar 7 --flag true sets variables, leaves positionals" \
  test "$(bash "$tmp/opts.sh" --foo-bar 7 --flag true a b)" = "7 true a b"
expect_fail "parse_options: unknown option is an error" bash "$tmp/opts.sh" --nope 1
expect_fail "parse_options: --name=value is an error (Kaldi's rule)" bash "$tmp/opts.sh" --foo-bar=3
expect_fail "parse_options: a boolean takes only true/false" bash "$tmp/opts.sh" --flag yes
echo 'foo_bar=from_config' >"$tmp/conf"
check "parse_options: --config is sourced, later options override" \
  test "$(bash "$tmp/opts.sh" --config "$tmp/conf" --flag true)" = "from_config true "
check "parse_options: --help exits 0" bash "$tmp/opts.sh" --help 2>/dev/null

# ---- run_jobs.sh: run.pl's JOB=1:N contract ----
run_jobs.sh JOB=1:4 --max-jobs-run 2 "$tmp/log/j.JOB.log" echo job JOB \| tr a-z A-Z
check "run_jobs: exit 0 when all jobs succeed" test $? -eq 0
check "run_jobs: JOB replaced in log name and command, pipe honoured" grep -qx "JOB 3" "$tmp/log/j.3.log"
check "run_jobs: run.pl's log header and footer" \
  bash -c "head -1 '$tmp/log/j.2.log' | grep -q '^# echo job 2 | tr' && grep -q '^# Ended (code 0)' '$tmp/log/j.2.log'"
expect_fail "run_jobs: a failing job fails the whole call" run_jobs.sh JOB=1:3 "$tmp/log/f.JOB.log" test JOB -ne 2
check "run_jobs: the failed job's log records its exit code" grep -q '^# Ended (code 1)' "$tmp/log/f.2.log"
expect_fail "run_jobs: several jobs sharing one log is refused" run_jobs.sh JOB=1:2 "$tmp/log/same.log" true
start=$(date +%s%N)
run_jobs.sh JOB=1:4 --max-jobs-run 4 "$tmp/log/s.JOB.log" sleep 1
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
# 4 one-second jobs in parallel take ~1 s; sequentially 4 s. 3 s leaves room for a loaded machine.
check "run_jobs: jobs run concurrently (${elapsed_ms} ms for 4 x 1 s)" test "$elapsed_ms" -lt 3000

# ---- split_rirs.sh: the paper's 773/194/242 split ----
for i in $(seq 1 1209); do echo "rir$i room$((i % 7)) 5 4 3 1 1 1 2 2 2"; done >"$tmp/meta1209"
local/split_rirs.sh --seed 3 "$tmp/meta1209" "$tmp/split" 2>/dev/null
check "split: 1209 RIRs -> exactly 773/194/242" \
  test "$(cat "$tmp"/split/{train,dev,test}.ids | wc -l) $(wc -l <"$tmp/split/train.ids") $(wc -l <"$tmp/split/dev.ids") $(wc -l <"$tmp/split/test.ids")" = "1209 773 194 242"
check "split: the three parts are disjoint and cover every RIR" \
  test "$(cat "$tmp"/split/{train,dev,test}.ids | sort -u | wc -l)" -eq 1209
shuf --random-source=<(yes) "$tmp/meta1209" >"$tmp/meta_shuffled"
local/split_rirs.sh --seed 3 "$tmp/meta_shuffled" "$tmp/split_b" 2>/dev/null
check "split: depends on (seed, id) only, not on the table's order" diff -q "$tmp/split/test.ids" "$tmp/split_b/test.ids"
local/split_rirs.sh --seed 4 "$tmp/meta1209" "$tmp/split_c" 2>/dev/null
check "split: another seed gives another split" bash -c "! diff -q '$tmp/split/test.ids' '$tmp/split_c/test.ids' >/dev/null"
head -n 170 "$tmp/meta1209" >"$tmp/meta170"
local/split_rirs.sh "$tmp/meta170" "$tmp/split170" 2>/dev/null
# 170 * 194/1209 = 27.3 -> 27; 170 * 242/1209 = 34.03 -> 34; train = the rest.
check "split: other counts are scaled (170 -> 109/27/34)" grep -q 'train=109 dev=27 test=34' "$tmp/split170/split.txt"
# Grouped by source position: 34 positions x 5 conditions (room ids differ per condition, as the
# demo's R3VIVAL table has them); no position may have RIRs in two splits.
for c in 000 025 050 075 100; do for p in $(seq 1 34); do
  echo "r$c-p$p room-$c 9.7 5.5 2.7 $p.0 2.0 1.4 6.2 2.75 1.35"; done; done >"$tmp/meta_pos"
local/split_rirs.sh --group-fields "3 4 5 6 7 8" "$tmp/meta_pos" "$tmp/split_pos" 2>/dev/null
pos_of() { sed 's/^r[0-9]*-//' "$tmp/split_pos/$1.ids" | sort -u; }
check "split: grouped, no source position in two splits" \
  test "$(cat <(pos_of train) <(pos_of dev) <(pos_of test) | sort | uniq -d | wc -l)" -eq 0
check "split: grouped, every RIR in one split, whole positions (multiples of 5)" \
  bash -c "test \$(cat '$tmp'/split_pos/{train,dev,test}.ids | sort -u | wc -l) -eq 170 &&
           for f in train dev test; do test \$(( \$(wc -l <'$tmp'/split_pos/\$f.ids) % 5 )) -eq 0 || exit 1; done"
check "split: grouped sizes near 109/27/34 and recorded" grep -q 'train=110 dev=30 test=30 .* groups=fields 3 4 5 6 7 8' "$tmp/split_pos/split.txt"
local/split_rirs.sh "$tmp/meta_pos" "$tmp/split_ungrouped" 2>/dev/null
check "split: without --group-fields positions are split apart (what the grouping prevents)" \
  test "$(cat <(sed 's/^r[0-9]*-//' "$tmp/split_ungrouped/train.ids" | sort -u) <(sed 's/^r[0-9]*-//' "$tmp/split_ungrouped/test.ids" | sort -u) | sort | uniq -d | wc -l)" -gt 0
expect_fail "split: a group field that is not a number is an error" local/split_rirs.sh --group-fields "x" "$tmp/meta_pos" "$tmp/split_bad"
printf 'a r 1 1 1 .1 .1 .1 .2 .2 .2\na r 1 1 1 .1 .1 .1 .2 .2 .2\nb r 1 1 1 .1 .1 .1 .2 .2 .2\n' >"$tmp/dup"
expect_fail "split: duplicate RIR ids are an error" local/split_rirs.sh "$tmp/dup" "$tmp/split_dup"

# ---- stage 2's hand-off: the metadata table, with the header run.sh adds, read by rir-room-list ----
{ echo "rir-id room-id Lx Ly Lz sx sy sz mx my mz"; cat "$tmp/meta170"; } >"$tmp/setups.txt"
rir-room-list --format=table --seed 5 "$tmp/setups.txt" "$tmp/rooms" 2>/dev/null
check "room list: rir-room-list reads the recipe's metadata table, one line per RIR with its room id" \
  test "$(grep -c '^rir[0-9]* room=5,4,3 src=1,1,1 mic=2,2,2 .*room-id=room[0-6]$' "$tmp/rooms")" -eq 170
check "room list: rir-simulate reads it" rir-simulate --fs=8000 --length=0.1 "$tmp/rooms" "$tmp/sim" 2>/dev/null

# ---- prepare_but_reverbdb.sh on a fabricated BUT ReverbDB tree ----
but=$tmp/BUT_ReverbDB
mkwav() { mkdir -p "$(dirname "$1")"; sox -n -r 16000 -b 16 -c 1 "$1" synth 0.05 sine 1000 2>/dev/null; }
mkroom() {  # <room> <W> <D> <H>
  mkdir -p "$but/$1"
  printf '$EnvWidth\t%s\r\n$EnvDepth\t%s\r\n$EnvHeight\t%s\r\n' "$2" "$3" "$4" >"$but/$1/env_meta.txt"
}
mkpos() {  # <room> <spkdir> <nn> <sx sy sz> <mic-id> <mx my mz>
  local d=$but/$1/MicID01/$2
  mkdir -p "$d/$3"
  printf '$EnvSpk1Width\t%s\n$EnvSpk1Depth\t%s\n$EnvSpk1Height\t%s\n' "$4" "$5" "$6" >"$d/spk_meta.txt"
  printf '$EnvMicID\t%s\n$EnvMic%sWidth\t%s\n$EnvMic%sDepth\t%s\n$EnvMic%sHeight\t%s\n' "$7" "$7" "$8" "$7" "$9" "$7" "${10}" >"$d/$3/mic_meta.txt"
  mkwav "$d/$3/RIR/IR_sweep_15s_45Hzto22kHz_FS16kHz.v00.wav"
  mkwav "$d/$3/silence/silence_16kHz_60sec.v00.wav"
}
mkroom VUT_FIT_C236 6.5 4.5 3
mkpos VUT_FIT_C236 SpkID01_20190503_S 01 1 1 1.5 1 4 2 1.2
mkpos VUT_FIT_C236 SpkID01_20190503_S 02 1 1 1.5 2 5 3 1.2
mkpos VUT_FIT_C236 SpkID02_20190504_S 01 1 1 1.5 1 4 2 1.2     # repeat of the first
mkpos VUT_FIT_C236 SpkID03_20190505_S 01 2 2 1.5 3 7 2 1.2     # microphone outside (x=7 > 6.5)
mkroom VUT_FIT_L227 10 3 8                                        # the staircase
mkpos VUT_FIT_L227 SpkID01_20190601_S 01 1 1 1 4 2 1.5 1
local/prepare_but_reverbdb.sh "$but" "$tmp/but_out" 2>/dev/null
check "BUT: staircase, repeat and outside-room RIRs dropped, counts logged" \
  grep -qx 'found=5 staircase_dropped=1 outside_room_dropped=1 repeats_dropped=1 kept=2' "$tmp/but_out/counts.txt"
check "BUT: metadata as <id> <room> W D H src mic (CRLF metadata read)" \
  grep -qx "VUT_FIT_C236-SpkID01_20190503_S-02 VUT_FIT_C236 6.5 4.5 3 1 1 1.5 5 3 1.2" "$tmp/but_out/meta.txt"
check "BUT: rir_list in Kaldi's format and a noise per kept position" \
  bash -c "grep -q '^--rir-id VUT_FIT_C236-SpkID01_20190503_S-01 --room-id VUT_FIT_C236 /' '$tmp/but_out/rir_list' && test \$(wc -l < '$tmp/but_out/noise.scp') -eq 2"
rm "$but/VUT_FIT_C236/MicID01/SpkID01_20190503_S/spk_meta.txt"
expect_fail "BUT: a missing metadata file is an error" local/prepare_but_reverbdb.sh "$but" "$tmp/but_out2"
check "BUT: a failed run leaves the previous output alone" test -s "$tmp/but_out/meta.txt"

# ---- prepare_librispeech.sh on a fabricated LibriSpeech part ----
ls_part=$tmp/LibriSpeech/dev-clean
for u in 84-121123-0000 84-121123-0001 174-50561-0000; do
  r=${u%%-*}; c=${u#*-}; c=${c%-*}
  mkdir -p "$ls_part/$r/$c"
  sox -n -r 16000 -b 16 -c 1 "$ls_part/$r/$c/$u.flac" synth 0.2 sine 300 2>/dev/null
  echo "$u WORDS OF $u" >>"$ls_part/$r/$c/$r-$c.trans.txt"
done
printf ';ID|SEX|SUBSET|MINUTES|NAME\n84   | F | dev-clean | 8.02 | Christie\n174  | M | dev-clean | 8.04 | Peter\n' >"$tmp/LibriSpeech/SPEAKERS.TXT"
local/prepare_librispeech.sh "$ls_part" "$tmp/ls_dev" 2>/dev/null
check "LibriSpeech: Kaldi's ids, speakers <reader>-<chapter>, flac pipes" \
  bash -c "grep -qx '84-121123-0001 84-121123' '$tmp/ls_dev/utt2spk' && grep -q '^174-50561-0000 flac -c -d -s .*174-50561-0000.flac |\$' '$tmp/ls_dev/wav.scp' && grep -qx '84-121123 f' '$tmp/ls_dev/spk2gender'"
check "LibriSpeech: the data dir is valid" validate-data-dir --no-feats "$tmp/ls_dev" 2>/dev/null
rx=$(awk 'NR == 1 {$1 = ""; print}' "$tmp/ls_dev/wav.scp")
check "LibriSpeech: its wav.scp pipe decodes (0.2 s of audio)" \
  bash -c "bash -c '${rx% |}' | sox -t wav - -n stat 2>&1 | grep -q 'Length (seconds): *0.200000'"
expect_fail "combine: a source without wav.scp is an error" local/combine_data_dirs.sh "$tmp/ls_comb" "$tmp/ls_dev" "$tmp/no_such_dir"
cp -r "$tmp/ls_dev" "$tmp/ls_dev2"
sed -i 's/^/x/' "$tmp/ls_dev2/wav.scp" "$tmp/ls_dev2/utt2spk" "$tmp/ls_dev2/text" "$tmp/ls_dev2/spk2gender"
sed -i 's/ \([0-9]*-[0-9]*\)$/ x\1/' "$tmp/ls_dev2/utt2spk"
local/combine_data_dirs.sh "$tmp/ls_comb" "$tmp/ls_dev" "$tmp/ls_dev2" 2>/dev/null
check "combine: union of two dirs is a valid dir of 6 utterances" \
  bash -c "validate-data-dir --no-feats '$tmp/ls_comb' 2>/dev/null && test \$(wc -l < '$tmp/ls_comb/utt2spk') -eq 6"

# ---- our validator agrees with Kaldi's rules on hand-made good and bad dirs ----
good=$tmp/vdir_good
mkdir -p "$good"
printf 'spkA-u1 /a/1.wav\nspkA-u2 cat /a/2.wav |\nspkB-u1 /b/1.wav\n' >"$good/wav.scp"
printf 'spkA-u1 spkA\nspkA-u2 spkA\nspkB-u1 spkB\n' >"$good/utt2spk"
printf 'spkA spkA-u1 spkA-u2\nspkB spkB-u1\n' >"$good/spk2utt"
printf 'spkA-u1 HELLO\nspkA-u2 WORLD\nspkB-u1 AGAIN\n' >"$good/text"
check "validator: a valid dir passes" local/check_data_dir.sh "$good"
bad() {  # <what> <sed-expr> <file>: a copy of the good dir with one file changed must fail
  rm -rf "$tmp/vbad"; cp -r "$good" "$tmp/vbad"; sed -i "$2" "$tmp/vbad/$3"
  expect_fail "validator rejects: $1" local/check_data_dir.sh "$tmp/vbad"
}
bad "unsorted wav.scp" '1{h;d};2{G}' wav.scp
bad "duplicate key" '2s/.*/spkA-u1 \/x.wav/' wav.scp
bad "spk2utt disagreeing with utt2spk" 's/ spkA-u2//' spk2utt
bad "text missing an utterance" '3d' text
bad "'~' in wav.scp" 's/1.wav/1.wav~/' wav.scp
rm -rf "$tmp/vbad"; cp -r "$good" "$tmp/vbad"
printf 'spkA-u1 spkB\nspkA-u2 spkA\nspkB-u1 spkB\n' >"$tmp/vbad/utt2spk"
printf 'spkA spkA-u2\nspkB spkA-u1 spkB-u1\n' >"$tmp/vbad/spk2utt"
expect_fail "validator rejects: utt2spk not sorted by speaker" local/check_data_dir.sh "$tmp/vbad"

# ---- collect_wer.sh: Table 2 from fabricated decode dirs ----
k=$tmp/kaldi
mkwer() {  # <set> <decode-dir-suffix> <wer...>: one wer_<i> file per value
  local d=$k/$1/exp/chain_cleaned/$2 i=10
  mkdir -p "$d"
  shift 2
  for w in "$@"; do
    echo "%WER $w [ 100 / 1000, 10 ins, 20 del, 70 sub ]" >"$d/wer_${i}_0.0"
    i=$((i + 1))
  done
}
mkwer gas tdnn_1d_sp/decode_test_farfield_fglarge 17.10 16.53 16.90
mkwer gas tdnn_1d_sp/decode_test_farfield_tglarge 17.26
mkwer gas tdnn_1d_sp/decode_test_farfield_tgmed 20.24
mkwer gas tdnn_1d_sp/decode_test_farfield_tgsmall 21.91 22.5
mkwer gas tdnn_1d_sp_online/decode_test_farfield_tgsmall 21.83
mkwer gas tdnn_1d_sp/decode_dev_farfield_fglarge 1.00          # another test set: ignored
mkwer gas_gsr_eq tdnn_1d_sp/decode_test_farfield_fglarge 13.24
table=$(local/collect_wer.sh --sets "clean gas gas_gsr_eq" --test-set test_farfield "$k")
check "collect_wer: header in the paper's column order" \
  test "$(echo "$table" | head -1)" = "| Training data | fglarge | tglarge | tgmed | tgsmall | online |"
check "collect_wer: best WER per decode, paper's row names and order" \
  test "$(echo "$table" | sed -n 3,5p)" = "$(printf '%s\n' '| clean (Baseline) | - | - | - | - | - |' \
    '| GAS | 16.53 | 17.26 | 20.24 | 21.91 | 21.83 |' '| G(GAS)+EQ | 13.24 | - | - | - | - |')"
check "collect_wer: missing decodes are counted" bash -c "echo '$table' | grep -q '(9 decode(s) missing'"
expect_fail "collect_wer: no WER at all is an error" local/collect_wer.sh --sets clean "$k"

# ---- asr/table2.py: the proxy's Table 2 at the level of training runs, from fabricated decodes ----
# 10 utterances of 20 characters and 5 words per run; each run's CER = its errors / 200. Test A, five
# runs (seeds) per set: GAS 60 61 59 60 60 errors (30.0 30.5 29.5 30.0 30.0 %), real 40 44 36 42 38
# (20 22 18 21 19 %), clean 100 each (50 %), ctl 50 52 48 51 49 (25 26 24 25.5 24.5 %). By hand:
# real - GAS per seed -10 -8.5 -11.5 -9 -11: mean -10, SD 1.2748, paired t = -17.5 on 4 df
# (p < 0.0001), 95 % CI -10 +- 2.7764 * 1.2748 / sqrt 5 = -11.58 .. -8.42, d_z = -7.84; ctl - real
# per seed 5 4 6 4.5 5.5: mean 5, SD 0.7906, CI +4.02 .. +5.98, one-sided p < 0.0001.
e=$tmp/asr_exp
mkrun() {  # <set> <seed> <test> <char-errors of the run, spread over 10 utterances>
  local d=$e/${1}_seed$2/decode_$3 u q=$(( $4 / 10 )) r=$(( $4 % 10 ))
  mkdir -p "$d"
  { echo "# utt ref_words word_errors ins del sub ref_chars char_errors ins del sub"
    for u in 0 1 2 3 4 5 6 7 8 9; do c=$(( q + (u < r ? 1 : 0) )); echo "u$u 5 2 0 0 2 20 $c 0 0 $c"; done; } >"$d/utt_errors"
}
k=0; for v in 60 61 59 60 60; do mkrun gas $k A $v; k=$((k + 1)); done
k=0; for v in 40 44 36 42 38; do mkrun real $k A $v; k=$((k + 1)); done
k=0; for v in 50 52 48 51 49; do mkrun ctl_t60x0.33 $k A $v; k=$((k + 1)); done
for k in 0 1 2 3 4; do mkrun clean $k A 100; done
t2=$(python3 local/asr/table2.py --sets "clean real gas ctl_t60x0.33" --seeds "0 1 2 3 4" --tests A --titles "test A" \
     --dose "real ctl_t60x0.33" "$e" 2>&1)
row() { echo "$t2" | grep "^| $1 |"; }
check "table2.py: real: mean 20.00 with its 95 % t interval (t(0.975, 4) * 1.5811 / sqrt 5 = 1.96)" \
  bash -c "echo '$(row 'real (oracle)')' | awk -F'|' '\$3 == \" 20.00 ± 1.96 \" {ok = 1} END {exit !ok}'"
check "table2.py: real vs GAS paired by seed: -10.00 (-11.58 .. -8.42), -33.3 %, d_z -7.84, p < 0.0001" \
  bash -c "echo '$(row 'real (oracle)')' | awk -F'|' '\$5 == \" -10.00 (-11.58 .. -8.42) \" && \$6 == \" -33.3 % \" && \$7 == \" -7.84 \" && \$8 == \" < 0.0001 \" {ok = 1} END {exit !ok}'"
check "table2.py: the GAS row has no comparison" bash -c "echo '$(row GAS)' | grep -q '| — | — | — | — | — |'"
check "table2.py: the control is labelled and its dose check passes (+5.00, CI +4.02 .. +5.98)" \
  bash -c "echo \"\$1\" | grep -q 'control: real, T60 x0.33 | 25.00' &&
           echo \"\$1\" | grep -q 'Dose-response (real -> ctl_t60x0.33).*+5.00 points paired by seed (95 % CI +4.02 .. +5.98), one-sided paired t p = < 0.0001.*PASS'" _ "$t2"
check "table2.py: the resolution line is printed" bash -c "echo \"\$1\" | grep -q '^Resolution (two-sided alpha 0.05'" _ "$t2"
check "table2.py: Student's t tail agrees with tables (P(T > 2.0 | 10 df) = 0.03669)" \
  python3 -c "import sys; sys.path.insert(0, 'local/asr'); import table2; sys.exit(abs(table2.t_sf(2.0, 10) - 0.036694) > 2e-6)"
# A dose chain that does not rise fails, and --require-dose turns that into exit status 3.
python3 local/asr/table2.py --sets "real gas" --seeds "0 1 2 3 4" --tests A --dose "gas real" --require-dose "$e" >/dev/null 2>&1
check "table2.py: a falling dose chain fails with exit status 3 under --require-dose" test $? -eq 3
# One seed (the tiny demo): the table prints means and differences, and no interval or p-value.
t1=$(python3 local/asr/table2.py --sets "real gas" --seeds "0" --tests A --dose "gas real" "$e" 2>&1)
check "table2.py: one seed gives differences without intervals or p-values (n/a), and no dose verdict of PASS" \
  bash -c "echo \"\$1\" | grep -q '^| real (oracle) | 20.00 | 40.00 | -10.00 (n/a) | -33.3 % | n/a | n/a | n/a |' &&
           ! echo \"\$1\" | grep -q PASS" _ "$t1"
rm "$e/gas_seed1/decode_A/utt_errors"
expect_fail "table2.py: a missing decode is an error" python3 local/asr/table2.py --sets "real gas" --seeds "0 1" --tests A "$e"

# ---- asr/make_real_speech_dir.sh: the real-speech test set from a speech tree like ../shared/data/speech ----
rs=$tmp/speech
mkdir -p "$rs/librispeech" "$rs/pocketsphinx/cards"
for f in librispeech/11-22-0001.wav pocketsphinx/book-0870.wav pocketsphinx/cards/001.wav; do
  sox -n -r 16000 -b 16 -c 1 "$rs/$f" synth 0.5 sine 300 gain -10
done
sox -n -r 16000 -b 16 -c 1 "$rs/librispeech/33-44-0000.flac" synth 0.5 sine 300 gain -10
sox -n -r 16000 -b 16 -c 1 "$rs/librispeech/33-44-0009.flac" synth 0.5 sine 300 gain -10   # no transcript
printf '11-22-0001\tHELLO WORLD\n' >"$rs/librispeech/trans.txt"
printf 'lbi-33-44-0000 A FLAC LINE\n' >"$rs/librispeech/mini_librispeech_text.txt"
printf '<s> he was not </s> (book-0870)\n' >"$rs/pocketsphinx/transcription"
printf '<s> ten of clubs </s> (001)\n' >"$rs/pocketsphinx/cards/cards.transcription"
local/asr/make_real_speech_dir.sh "$rs" "$tmp/rs_dir" 2>/dev/null
check "real speech: every transcribed utterance, none without a transcript" \
  test "$(cut -d' ' -f1 "$tmp/rs_dir/text" | tr '\n' ' ')" = "11-22-0001 33-44-0000 ps-austen-0870 ps-cards-001 "
check "real speech: transcripts and speakers as given" \
  bash -c "grep -qx 'ps-cards-001 ten of clubs' '$tmp/rs_dir/text' && grep -qx '33-44-0000 33-44' '$tmp/rs_dir/utt2spk'"
check "real speech: a valid data dir whose FLAC pipe decodes" \
  bash -c "validate-data-dir --no-feats '$tmp/rs_dir' 2>/dev/null && bash -c \"\$(awk '/flac/ {\$1 = \"\"; sub(/ [|]\$/, \"\"); print}' '$tmp/rs_dir/wav.scp')\" | sox -t wav - -n stat 2>&1 | grep -q 'Length (seconds): *0.500000'"
local/asr/make_real_speech_dir.sh "$tmp/no_speech" "$tmp/rs_none" 2>/dev/null
check "real speech: an absent speech dir exits 2 (the caller skips the test set)" test $? -eq 2

# ---- remove_tsrir_files.sh: only what tsrir wrote goes ----
mkdir -p "$tmp/owned"
echo a >"$tmp/owned/a.wav"; echo mine >"$tmp/owned/notes.txt"
printf '# tsrir\na.wav\t2\t0\tprog\t.\n' >"$tmp/owned/.tsrir-owned"
local/remove_tsrir_files.sh "$tmp/owned" 2>/dev/null
check "remove_tsrir_files: the listed file and the marker go, a user's file and the dir stay" \
  bash -c "test ! -e '$tmp/owned/a.wav' && test ! -e '$tmp/owned/.tsrir-owned' && test -f '$tmp/owned/notes.txt'"

# ---- the demo corpus's stand-ins (a clone without ../shared/data) ----
local/make_demo_data.sh --size tiny --shared-data "$tmp/no_shared_data" --seed 1 "$tmp/demo_standin" 2>"$tmp/standin.log"
check "stand-ins: demo corpus made without ../shared/data" test -f "$tmp/demo_standin/SOURCES"
check "stand-ins: every part marked STAND-IN" test "$(grep -c 'STAND-IN' "$tmp/demo_standin/SOURCES")" -eq 3
check "stand-ins: espeak-ng speech at 16 kHz, 3/1/2 utterances with transcripts" \
  bash -c "test \$(cat '$tmp'/demo_standin/speech/*/text | wc -l) -eq 6 && soxi -r \$(awk 'NR == 1 {print \$2}' '$tmp/demo_standin/speech/test_clean/wav.scp') | grep -qx 16000"
check "stand-ins: one simulated RIR per metadata line, 16 kHz" \
  bash -c "test \$(wc -l < '$tmp/demo_standin/rirs/rir.scp') -eq \$(wc -l < '$tmp/demo_standin/rirs/meta.txt') && soxi -r \$(awk 'NR == 1 {print \$2}' '$tmp/demo_standin/rirs/rir.scp') | grep -qx 16000"
check "stand-ins: generated noise is not silent" \
  bash -c "sox \$(awk 'NR == 1 {print \$2}' '$tmp/demo_standin/noise/noise.scp') -n stat 2>&1 | awk '/RMS +amplitude/ {exit !(\$3 > 0.001)}'"

if [ "$failures" -gt 0 ]; then echo "$failures check(s) failed" >&2; exit 1; fi
echo "all recipe unit checks passed"
