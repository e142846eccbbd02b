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
AdditiveSignal planned_noise_signal(const PlannedNoise& planned, std::shared_ptr<const std::vector<float>> noise,
                                    const PreparedRir* rir, double sample_rate_hz);

}  // namespace tsrir
