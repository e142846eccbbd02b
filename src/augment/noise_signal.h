// The signal of one planned noise (noise_type.h) as the wav.scp pipe makes it, for the paths
// that reverberate in memory or in passes (--write-wavs): Kaldi's nested
// `wav-reverberate [--impulse-response=<rir>] [--duration=<s>] <noise> -` run in memory with
// wav-reverberate's defaults, then rounded to 16 bits as the pipe between the two programs does.
#pragma once
#include <memory>
#include <vector>

#include "augment/noise_type.h"
#include "augment/reverberate.h"

namespace tsrir {

// `noise` and `rir` (null = none) are at `sample_rate_hz`. Equal, sample for sample, to what the
// pipe adds when noise, RIR and speech share one sample rate (otherwise the pipe resamples after
// the nested step and the results differ by the resampler's rounding).
// Kaldi's nested `wav-reverberate [--impulse-response=<rir>] [--duration=<s>] <noise> -` in
// process: `noise` convolved with `rir` (null = none) with wav-reverberate's defaults (shifted,
// normalised), repeated or cut to `duration_s` (0 = as is), rounded to 16 bits as the pipe between
// the two programs does. Used by wav-reverberate's --additive-impulse-responses/--additive-durations
// and by reverberate-data's materialised path, so both equal the nested pipe. Without an RIR the
// result depends only on the first int(fs * duration) samples of `noise` (when it is longer): a
// caller may pass just those.
// `noise_is_int16`: its samples are 16-bit PCM values, which the pipe's rounding to 16 bits leaves
// as they are when there is no RIR (the rounding is then skipped). `kaldi_compat`: as Kaldi's own
// nested program computes it (ReverbOptions::kaldi_compat), truncated to 16 bits.
// `noise` is only read (with an RIR not copied at all, without one only the samples the result
// keeps); given as an rvalue, its buffer becomes the result when there is no RIR and it is kept or
// cut. The same values either way.
std::vector<float> nested_noise_signal(const std::vector<float>& noise, double sample_rate_hz, const PreparedRir* rir,
                                       double duration_s, bool noise_is_int16 = false, bool kaldi_compat = false);
std::vector<float> nested_noise_signal(std::vector<float>&& noise, double sample_rate_hz, const PreparedRir* rir,
                                       double duration_s, bool noise_is_int16 = false, bool kaldi_compat = false);

AdditiveSignal planned_noise_signal(const PlannedNoise& planned, std::shared_ptr<const std::vector<float>> noise,
                                    const PreparedRir* rir, double sample_rate_hz);

}  // namespace tsrir
