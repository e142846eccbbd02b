#include "sim/source_directivity.h"

#include <cmath>

#include "sim/image_sources.h"
#include "util/error.h"

namespace tsrir::sim {

std::string directivity_key(int band) { return "di" + octave_band_label(kOctaveCentersHz[band]); }

SourceDirectivityComponent::SourceDirectivityComponent(ComponentParams& params) {
  for (int b = 0; b < kNumOctaveBands; ++b) {
    di_db_[b] = params.number(directivity_key(b), 0.0);
    if (!(std::abs(di_db_[b]) <= 20.0)) {
      throw Error("model component directivity: " + directivity_key(b) + " must be within +-20 dB");
    }
  }
}

void SourceDirectivityComponent::render_bands(const RenderContext& ctx, BandSignals& bands) const {
  // ism sets the transition time; its images, the direct sound first, arrive before it.
  if (!(ctx.facts.transition_time_s > ctx.facts.direct_delay_s)) return;
  const double kPi = 3.14159265358979323846;
  const double direct_amplitude = 1.0 / (4.0 * kPi * ctx.room.source_mic_distance_m());
  BandValues extra{};
  for (int b = 0; b < kNumOctaveBands; ++b) extra[b] = (std::pow(10.0, di_db_[b] / 20.0) - 1.0) * direct_amplitude;
  add_fractional_impulse(ctx.facts.direct_delay_s * ctx.sample_rate_hz, extra, bands);
}

}  // namespace tsrir::sim
