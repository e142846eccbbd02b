#include "sim/diffuse_tail.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tsrir::sim {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

DiffuseTailComponent::DiffuseTailComponent(ComponentParams&) {}

double DiffuseTailComponent::max_decay_time_s(const RoomSpec& room) const {
  const BandValues t60 = eyring_t60_s(room);
  return *std::max_element(t60.begin(), t60.end());
}

void DiffuseTailComponent::render_bands(const RenderContext& ctx, BandSignals& bands) const {
  const RoomSpec& room = ctx.room;
  const double fs = ctx.sample_rate_hz;
  const size_t n = ctx.num_samples;
  const RenderFacts& facts = ctx.facts;
  const size_t first = std::min(n, static_cast<size_t>(std::ceil(facts.direct_delay_s * fs)));
  if (first >= n) return;

  // Uniform noise on [-sqrt(3), sqrt(3)): variance 1, and an order of magnitude cheaper than
  // Gaussian draws; after band filtering it is Gaussian anyway.
  Rng rng = ctx.rng_for(name());
  std::vector<float> noise(n - first);
  const double half_width = std::sqrt(3.0);
  for (float& x : noise) x = static_cast<float>(rng.uniform(-half_width, half_width));

  const BandValues rate = eyring_decay_rate_per_s(room);
  const double density_per_sample = room.speed_of_sound_m_s / (4.0 * kPi * room.volume_m3() * fs);
  const double reflections_per_s = room.speed_of_sound_m_s * room.surface_area_m2() / (4.0 * room.volume_m3());
  const size_t transition = std::min(n, static_cast<size_t>(std::ceil(facts.transition_time_s * fs)));

  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (std::isinf(rate[b])) continue;  // a = 1: no reverberation in this band
    double level = 1.0;
    if (facts.transition_time_s > 0.0 && facts.window_diffuse_energy[b] > 0.0) {
      level = std::clamp(facts.window_image_energy[b] / facts.window_diffuse_energy[b], 0.25, 4.0);
    }
    // Amplitude envelope sqrt(level * density * exp(-rate t)), advanced multiplicatively.
    const double t0 = first / fs;
    double amp = std::sqrt(level * density_per_sample) * std::exp(-0.5 * rate[b] * t0);
    const double amp_step = std::exp(-0.5 * rate[b] / fs);
    // Specular share (1 - s)^k(t) = exp(ln(1 - s) * reflections_per_s * t).
    const double s = room.scattering[b];
    const double log_specular_rate = s >= 1.0 ? -INFINITY : std::log1p(-s) * reflections_per_s;
    double specular = std::exp(log_specular_rate * t0);
    const double specular_step = std::exp(log_specular_rate / fs);
    float* out = bands.band[b].data();
    const float* white = noise.data() - first;
    size_t i = first;
    for (; i < transition; ++i) {
      out[i] += static_cast<float>(amp * std::sqrt(1.0 - specular) * white[i]);
      amp *= amp_step;
      specular *= specular_step;
    }
    for (; i < n; ++i) {
      out[i] += static_cast<float>(amp * white[i]);
      amp *= amp_step;
    }
  }
}

}  // namespace tsrir::sim
