// Point-source noise (Kaldi's --noise-type point-source): with probability
// --pointsource-noise-addition-probability, 1..N of them per recording (N = floor(
// --max-noises-per-minute * duration / 60), none when N < 1), each drawn by its probability and
// convolved with an RIR drawn from the recording's room (a second source in the same room).
// Background ones (--bg-fg-type background) are extended to the recording's duration from time 0
// at an SNR from --background-snrs; foreground ones are added once, unextended, at a start time
// uniform over the recording (rounded to 10 ms, as Kaldi) at an SNR from --foreground-snrs.
#include <cmath>

#include "augment/augment_plan.h"
#include "augment/noise_type.h"

namespace tsrir {
namespace {

class PointSourceNoise : public NoiseType {
 public:
  std::string name() const override { return "point-source"; }

  void check(const NoiseChoice&, const std::set<std::string>&) const override {}

  // Kaldi: within each set smoothed towards uniform and scaled to the set's weight, then all
  // point-source noises normalised to sum to 1 (sets without point sources lose their mass).
  void assign_probabilities(const std::vector<NoiseChoice*>& entries, const std::vector<double>& set_weights,
                            double smoothing_weight) const override {
    std::map<size_t, std::vector<NoiseChoice*>> by_set;
    for (NoiseChoice* n : entries) by_set[n->set].push_back(n);
    double total = 0.0;
    for (auto& [set, noises] : by_set) {
      std::vector<std::optional<double>> given;
      for (NoiseChoice* n : noises) given.push_back(n->given_probability);
      std::vector<double> p = kaldi_smoothed_probabilities(given, smoothing_weight, set_weights.at(set),
                                                           noises.front()->where.substr(0, noises.front()->where.rfind(':')));
      for (size_t i = 0; i < noises.size(); ++i) {
        noises[i]->probability = p[i];
        total += p[i];
      }
    }
    if (total > 0)
      for (NoiseChoice* n : entries) n->probability /= total;
  }

  void plan(const NoisePlanContext& context, std::vector<PlannedNoise>* out) const override {
    const std::vector<size_t> candidates = context.sources.noises_of_type(name());
    if (candidates.empty()) return;
    const long max_noises = context.options.max_noises_per_recording > 0
                                ? context.options.max_noises_per_recording
                                : static_cast<long>(std::floor(context.options.max_noises_per_minute *
                                                               context.duration_s / 60.0));
    if (!(context.rng.uniform() < context.options.pointsource_noise_addition_probability) || max_noises < 1) return;
    const long count = 1 + static_cast<long>(context.rng.below(static_cast<uint64_t>(max_noises)));
    const auto room = context.sources.rirs_by_room.find(context.room);
    for (long k = 0; k < count; ++k) {
      const size_t noise = draw_noise(context.sources, candidates, context.rng.uniform());
      long rir = -1;
      const double u_rir = context.rng.uniform();
      if (context.options.point_source_noise_rir && room != context.sources.rirs_by_room.end()) {
        std::vector<double> w;
        for (size_t r : room->second) w.push_back(context.sources.rirs[r].probability);
        rir = static_cast<long>(room->second[weighted_index(w, u_rir)]);
      }
      if (context.sources.noises[noise].bg_fg_type == BgFgType::kForeground) {
        PlannedNoise p;
        p.noise = static_cast<long>(noise);
        p.rir = rir;
        p.foreground = true;
        p.start_time_s = std::round(context.rng.uniform() * context.duration_s * 100.0) / 100.0;
        p.snr_db = pipe_rounded(context.foreground_snrs.next(context.rng));
        out->push_back(p);
      } else {
        out->push_back(background_noise(context, noise, rir));
      }
    }
  }
};

}  // namespace

std::unique_ptr<NoiseType> make_point_source_noise_type() { return std::make_unique<PointSourceNoise>(); }

}  // namespace tsrir
