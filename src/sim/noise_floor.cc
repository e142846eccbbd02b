#include "sim/noise_floor.h"

#include <algorithm>
#include <cmath>

#include "sim/spectral_shaping.h"
#include "util/error.h"

namespace tsrir::sim {

double noise_tilt_power_gain(double f_hz, double tilt_db_per_octave, double min_hz, double max_hz) {
  const double f = std::clamp(f_hz, std::max(min_hz, 1.0), std::max(max_hz, min_hz));
  return std::pow(10.0, tilt_db_per_octave * std::log2(f / 1000.0) / 10.0);
}

NoiseFloorComponent::NoiseFloorComponent(ComponentParams& params)
    : level_db_(params.number("level_db", -100.0)),
      tilt_db_per_octave_(params.number("tilt_db_per_octave", 0.0)),
      min_hz_(params.number("min_hz", 20.0)),
      max_hz_(params.number("max_hz", 1e9)) {
  if (!(min_hz_ > 0.0 && max_hz_ >= min_hz_)) throw Error("model component noise_floor: need 0 < min_hz <= max_hz");
  if (!(level_db_ >= -300.0 && level_db_ <= 0.0)) throw Error("model component noise_floor: level_db must be in [-300, 0]");
  if (!(std::abs(tilt_db_per_octave_) <= 12.0)) {
    throw Error("model component noise_floor: tilt_db_per_octave must be within +-12");
  }
}

void NoiseFloorComponent::process_rir(const RenderContext& ctx, std::vector<float>& samples) const {
  double energy = 0.0;
  for (float x : samples) energy += static_cast<double>(x) * x;
  Rng rng = ctx.rng_for(name());
  std::vector<float> noise(samples.size());
  for (float& x : noise) x = static_cast<float>(rng.normal());
  struct Arg { double tilt, lo, hi; };
  const Arg arg{tilt_db_per_octave_, min_hz_, max_hz_};
  noise = zero_phase_filter(noise, ctx.sample_rate_hz, 0,
                            [](double f, const void* a) {
                              const Arg* g = static_cast<const Arg*>(a);
                              return std::sqrt(noise_tilt_power_gain(f, g->tilt, g->lo, g->hi));
                            },
                            &arg);
  const double sigma = std::sqrt(energy * std::pow(10.0, level_db_ / 10.0));
  for (size_t i = 0; i < samples.size(); ++i) samples[i] += static_cast<float>(sigma * noise[i]);
}

}  // namespace tsrir::sim
