#!/usr/bin/env bash
# Golden outputs of reverberate-data (pipes and --write-wavs, in memory and streamed, Kaldi's noise
# rules and tsrir's extensions, segments and the optional tables), the pipes' audio, and
# wav-reverberate: the bytes a refactoring must keep (tests/common/golden/compare.py).
# Usage: golden_test.sh <bin-dir>
source "$(dirname "${BASH_SOURCE[0]}")/../common/golden/golden.sh" "$1" "$(dirname "${BASH_SOURCE[0]}")/golden"

kaldi_lists=(--rir-set-parameters '0.6, lists/rir_list_a' --rir-set-parameters lists/rir_list_b
             --noise-set-parameters lists/noise_list)
# Kaldi's rules, pipes, two copies; the pipes' audio.
"$bin/reverberate-data" "${kaldi_lists[@]}" --foreground-snrs 15:5:0 --background-snrs 20:10 \
  --max-noises-per-minute 3 --num-replications 2 --random-seed 3 in "$out/kaldi" 2>/dev/null
run_pipes "$out/kaldi" "$out/kaldi_pipes"
# The same through --pipe-dialect=kaldi and a named program (text only).
"$bin/reverberate-data" "${kaldi_lists[@]}" --pipe-dialect kaldi --pipe-program wav-reverberate \
  --random-seed 4 in "$out/dialect" 2>/dev/null
# tsrir's extensions: one looped noise from a random offset, no point-source RIR, SNR ranges, wavs.
"$bin/reverberate-data" --rir-set-parameters lists/rir.scp --noise-set-parameters lists/noise.scp \
  --background-snrs 1..2 --max-noises-per-recording 1 --point-source-noise-rir none --noise-start random \
  --write-wavs "$out/looped_wavs" --num-threads 2 --random-seed 7 in "$out/looped" 2>/dev/null
# Streamed (recordings over 0.6 s read in passes), probabilities below 1, no shift or normalisation.
"$bin/reverberate-data" "${kaldi_lists[@]}" --max-in-memory-duration 0.6 --shift-output false \
  --normalize-output false --speech-rvb-probability 0.7 --isotropic-noise-addition-probability 0.5 \
  --pointsource-noise-addition-probability 0.8 --write-wavs "$out/streamed_wavs" --random-seed 8 \
  in "$out/streamed" 2>/dev/null
# Segments, reco2file_and_channel and vad.scp renamed per copy; the original kept; full-signal SNRs.
"$bin/reverberate-data" --rir-set-parameters lists/rir_list_a --noise-set-parameters lists/noise_list \
  --include-original-data true --num-replications 2 --prefix rv --snr-reference full --random-seed 11 \
  --write-wavs "$out/segments_wavs" in_seg "$out/segments" 2>/dev/null

mkdir -p "$out/wav_reverberate"
"$bin/wav-reverberate" --impulse-response=rirs/a1.wav --additive-signals='noise/ps_bg.wav,noise/fg_short.wav' \
  --snrs='10,5' --start-times='0,0.3' --shift-output=true audio/spkA-u2.wav "$out/wav_reverberate/shifted.wav" 2>/dev/null
"$bin/wav-reverberate" --impulse-response=rirs/b1.wav --additive-signals=noise/iso_a.wav --snrs=3 \
  --start-times=0 --duration=0.9 --normalize-output=false --volume=0.5 audio/spkA-u1.wav \
  "$out/wav_reverberate/duration.wav" 2>/dev/null
"$bin/wav-reverberate" --impulse-response=rirs/a2.wav --kaldi-compat=true --shift-output=true \
  audio/spkB-u3.wav "$out/wav_reverberate/kaldi_compat.wav" 2>/dev/null
golden_finish
