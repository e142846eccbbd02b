// The original's input conventions (docs/reference/spec-digest.md §3.1): RIRs at 16 kHz, only the first 16384
// samples kept, shorter ones zero-padded at the end, each divided by its peak |x|.
#pragma once
#include <cstddef>
#include <vector>

#include "io/signal.h"

namespace tsrir {

constexpr size_t kGanSliceLength = 16384;
constexpr double kGanSampleRateHz = 16000.0;

struct GanInput {
  std::vector<float> samples;   // kGanSliceLength samples, peak-normalised
  double peak = 0.0;            // max |x| of the kept samples before normalisation
  size_t length = 0;            // samples kept (<= kGanSliceLength)
  bool cropped = false;         // the RIR was longer than kGanSliceLength
};

// `rir` must already be at kGanSampleRateHz. Throws Error naming the id for a silent RIR (its
// peak cannot be normalised).
GanInput prepare_gan_input(const Signal& rir);

}  // namespace tsrir
