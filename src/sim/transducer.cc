#include "sim/transducer.h"

#include <cmath>

#include "dsp/convolve.h"
#include "dsp/fft.h"
#include "sim/spectral_shaping.h"
#include "util/error.h"

namespace tsrir::sim {

std::string transducer_gain_key(int band) { return "g" + octave_band_label(kOctaveCentersHz[band]); }

std::vector<float> transducer_filter(const BandValues& gains_db, double sample_rate_hz) {
  // 64 ms of filter: enough for octave-smooth responses down to 62.5 Hz.
  const size_t taps = static_cast<size_t>(std::llround(0.064 * sample_rate_hz));
  const size_t fft_size = next_fast_fft_size(8 * taps);  // even (a multiple of 8), as minimum_phase_fir needs
  std::vector<double> mag_db(fft_size / 2 + 1);
  for (size_t k = 0; k < mag_db.size(); ++k) mag_db[k] = interpolate_band_db(gains_db, k * sample_rate_hz / fft_size);
  return minimum_phase_fir(mag_db, fft_size, taps);
}

TransducerComponent::TransducerComponent(ComponentParams& params) {
  for (int b = 0; b < kNumOctaveBands; ++b) {
    gains_db_[b] = params.number(transducer_gain_key(b), 0.0);
    if (!(std::abs(gains_db_[b]) <= 60.0)) {
      throw Error("model component transducer: " + transducer_gain_key(b) + " must be within +-60 dB");
    }
  }
}

void TransducerComponent::process_rir(const RenderContext& ctx, std::vector<float>& samples) const {
  const size_t n = samples.size();
  std::vector<float> y = fft_convolve(samples, transducer_filter(gains_db_, ctx.sample_rate_hz));
  y.resize(n);
  samples = std::move(y);
}

}  // namespace tsrir::sim
