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

namespace {

// The direct sound as "ism" rendered it, per band: 1 / (4 pi r) times the microphone's pattern
// gain for the direction it arrives from and the source's for the direction it leaves in.
BandValues ism_direct_amplitudes(const RoomSpec& room) {
  const double kPi = 3.14159265358979323846;
  const double r = room.source_mic_distance_m();
  Vec3 departure{};  // from the source towards the microphone
  for (int i = 0; i < 3; ++i) departure[i] = (room.mic_m[i] - room.source_m[i]) / r;
  const Vec3 arrival{-departure[0], -departure[1], -departure[2]};
  const double mic = polar_gain(room.mic_pattern.value_or(PolarPattern::kOmni), room.mic_axis, arrival);
  BandValues amplitudes = source_pattern_gains(room, departure);
  for (double& a : amplitudes) a *= mic / (4.0 * kPi * r);
  return amplitudes;
}

}  // namespace

double directivity_direct_gain(double di_db, const RoomSpec& room, int band) {
  // The pattern's own directivity factor on its axis, Q_p = 1 / mean(g^2) (g = 1 on axis).
  const double pattern_q = 1.0 / polar_diffuse_energy(source_pattern_in_band(room, band));
  return std::pow(10.0, di_db / 20.0) / std::sqrt(pattern_q);
}

void SourceDirectivityComponent::render_bands(const RenderContext& ctx, BandSignals& bands) const {
  // ism sets the transition time; its images, the direct sound first, arrive before it.
  if (!(ctx.facts.transition_time_s > ctx.facts.direct_delay_s)) return;
  const BandValues direct_amplitude = ism_direct_amplitudes(ctx.room);
  BandValues extra{};
  for (int b = 0; b < kNumOctaveBands; ++b)
    extra[b] = (directivity_direct_gain(di_db_[b], ctx.room, b) - 1.0) * direct_amplitude[b];
  add_fractional_impulse(ctx.facts.direct_delay_s * ctx.sample_rate_hz, extra, bands);
}

}  // namespace tsrir::sim
