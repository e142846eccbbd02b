#!/usr/bin/env bash
# The demo never downloads, also in a Kaldi user's shell (issue 32): with KALDI_ROOT exported (a fake
# Kaldi tree here: parse_options.sh, run.pl and validate_data_dir.sh as Kaldi lays them out, no
# binaries) and wget/curl replaced on PATH by stubs that record any call and fail, `run.sh --demo`
# must plan the proxy recogniser for stage 8 (it used to pick Kaldi and run download_lm.sh), and
# `--asr kaldi` in demo mode must plan Kaldi with the offline LM (--lm-text), never openslr's
# download. Stage 0 runs for real through the fake Kaldi's option parser; the other stages are not
# needed to see stage 8's choice, which run.sh makes and logs before any stage. Then stage 1 (the
# training transcripts) and stage 8 itself with --asr kaldi: it writes the LM text it planned and
# runs local/kaldi/run_asr.sh with it until the fake Kaldi's missing programs stop it, without any
# download; the full experiment's stage 8, run the same way, does call wget (the control).
# Env: TSRIR_BIN = the directory of the built programs (set by CTest).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
recipe=$(cd "$here/../../egs/librispeech_farfield" && pwd)
: "${TSRIR_BIN:?TSRIR_BIN must name the directory of the built programs}"
tmp=$(mktemp -d)
trap '[ -n "${KEEP:-}" ] || rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { local what=$1; shift; if "$@"; then echo "ok: $what"; else fail "$what"; fi; }

fake=$tmp/kaldi
mkdir -p "$fake/tools/config" "$fake/egs/wsj/s5/utils" "$tmp/netbin"
: >"$fake/tools/config/common_path.sh"
cp "$recipe/local/parse_options.sh" "$fake/egs/wsj/s5/utils/parse_options.sh"
printf '#!/usr/bin/env bash\nexec run_jobs.sh "$@"\n' >"$fake/egs/wsj/s5/utils/run.pl"
printf '#!/usr/bin/env bash\necho "validate_data_dir.sh $*" >>%q\n' "$tmp/kaldi_calls" >"$fake/egs/wsj/s5/utils/validate_data_dir.sh"
for tool in wget curl; do
  printf '#!/usr/bin/env bash\necho "%s $*" >>%q\nexit 1\n' "$tool" "$tmp/network_calls" >"$tmp/netbin/$tool"
done
chmod +x "$fake"/egs/wsj/s5/utils/* "$tmp"/netbin/*
export KALDI_ROOT=$fake PATH=$tmp/netbin:$TSRIR_BIN:$PATH

w=$tmp/demo
common=(--demo --demo-size tiny --data "$w/data" --exp "$w/exp" --results "$w/RESULTS.md")
"$recipe/run.sh" "${common[@]}" --stop-stage 0 >"$tmp/out0" 2>"$tmp/err0"
rc=$?
check "run.sh --demo with KALDI_ROOT exported runs (stage 0; exit $rc)" test $rc -eq 0
[ $rc -eq 0 ] || tail -n 20 "$tmp/err0" >&2
check "stage 0 made the demo corpus" grep -q '^run.sh: stage 0 done' "$tmp/err0"
check "stage 8 is planned as the proxy recogniser, not Kaldi" \
  grep -q '^run.sh: stage 8 uses the proxy recogniser (asr-train/asr-decode; no Kaldi, no downloads)' "$tmp/err0"

"$recipe/run.sh" "${common[@]}" --asr kaldi --stage 1 --stop-stage 1 >"$tmp/out1" 2>"$tmp/err1"
rc=$?
check "--asr kaldi in the demo plans the offline LM (--lm-text)" \
  grep -q "^run.sh: stage 8 uses Kaldi (local/kaldi/run_asr.sh, LM built offline from the demo's transcripts: --lm-text " "$tmp/err1"
check "stage 1 made the training data dir (exit $rc)" test $rc -eq 0 -a -s "$w/data/train_clean/text"
# Stage 8 with Kaldi for real, on stage 1's training dir and stand-ins for stage 7's far-field dirs
# (copies of the clean ones; one training set): run_asr.sh starts and stops at the first program the
# fake Kaldi lacks (utils/prepare_lang.sh), after building its lexicon from the LM text.
for d in test_clean dev_clean; do cp -r "$w/data/$d" "$w/data/${d}_rvb_real"; done
"$recipe/run.sh" "${common[@]}" --asr kaldi --train-sets clean --stage 8 --stop-stage 8 >"$tmp/out8" 2>"$tmp/err8"
check "stage 8 --asr kaldi wrote the LM text from the training transcripts" \
  bash -c "cut -d' ' -f2- '$w/data/train_clean/text' | cmp -s - '$w/exp/kaldi/lm_text.txt'"
check "stage 8 --asr kaldi reached run_asr.sh's offline LM (its lexicon from the LM text)" \
  test -s "$w/exp/kaldi/clean/data/local/lm_small/words.txt"
check "stage 8 --asr kaldi did not reach for openslr's LM" bash -c "! grep -q 'download_lm\|openslr' '$tmp/err8'"
check "no network tool was called by the demo" test ! -e "$tmp/network_calls"
[ -e "$tmp/network_calls" ] && cat "$tmp/network_calls" >&2

# Positive control: the full experiment's stage 8 with Kaldi does download openslr's LM, and the
# stubs see it (so the checks above could fail).
cp -r "$w/data/train_clean" "$w/data/train_clean_460"
"$recipe/run.sh" --data "$w/data" --exp "$w/exp_full" --results "$w/RESULTS_full.md" --asr kaldi --train-sets clean \
  --stage 8 --stop-stage 8 >/dev/null 2>"$tmp/err_full"
check "control: the full experiment's stage 8 calls wget for openslr's LM (seen by the stub)" \
  grep -q '^wget .*openslr.org/resources/11' "$tmp/network_calls"

if [ "$failures" -gt 0 ]; then echo "$failures check(s) failed" >&2; exit 1; fi
echo "all checks passed"
