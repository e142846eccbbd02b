#include "augment/noise_type.h"

#include "augment/augment_plan.h"

namespace tsrir {

std::unique_ptr<NoiseType> make_isotropic_noise_type();     // noise_isotropic.cc
std::unique_ptr<NoiseType> make_point_source_noise_type();  // noise_point_source.cc

const std::vector<std::unique_ptr<NoiseType>>& noise_types() {
  static const std::vector<std::unique_ptr<NoiseType>> types = [] {
    std::vector<std::unique_ptr<NoiseType>> v;
    v.push_back(make_isotropic_noise_type());
    v.push_back(make_point_source_noise_type());
    return v;
  }();
  return types;
}

const NoiseType* find_noise_type(const std::string& name) {
  for (const auto& t : noise_types())
    if (t->name() == name) return t.get();
  return nullptr;
}

size_t draw_noise(const AugmentSources& sources, const std::vector<size_t>& candidates, double u) {
  std::vector<double> w;
  for (size_t i : candidates) w.push_back(sources.noises[i].probability);
  return candidates[weighted_index(w, u)];
}

PlannedNoise background_noise(const NoisePlanContext& context, size_t noise, long rir) {
  PlannedNoise p;
  p.noise = static_cast<long>(noise);
  p.rir = rir;
  p.start_time_s = 0.0;
  if (context.options.random_noise_start) {
    p.loop = true;
    p.offset_fraction = context.rng.uniform();
  } else {
    p.extend_to_s = pipe_rounded(context.duration_s);
  }
  p.snr_db = pipe_rounded(context.background_snrs.next(context.rng));
  return p;
}

}  // namespace tsrir
