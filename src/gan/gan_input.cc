#include "gan/gan_input.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace tsrir {

GanInput prepare_gan_input(const Signal& rir) {
  if (std::abs(rir.sample_rate_hz - kGanSampleRateHz) > 1e-6) {
    throw Error("RIR '" + rir.id + "' is at " + std::to_string(rir.sample_rate_hz) +
                " Hz; TS-RIRGAN works at 16000 Hz (resample when loading)");
  }
  GanInput input;
  input.length = std::min(rir.samples.size(), kGanSliceLength);
  input.cropped = rir.samples.size() > kGanSliceLength;
  input.samples.assign(kGanSliceLength, 0.0f);
  double peak = 0.0;
  for (size_t n = 0; n < input.length; ++n) peak = std::max(peak, std::abs(double(rir.samples[n])));
  if (!(peak > 0.0)) {
    throw Error("RIR '" + rir.id + "' is silent in its first " + std::to_string(input.length) +
                " samples: cannot peak-normalise it");
  }
  input.peak = peak;
  for (size_t n = 0; n < input.length; ++n) input.samples[n] = float(rir.samples[n] / peak);
  return input;
}

}  // namespace tsrir
