// Isotropic noise (Kaldi's --noise-type isotropic): recorded in one room (--room-linkage), added
// whole, not reverberated again, to recordings whose RIR draw fell in that room (also when the
// speech itself is not reverberated: Kaldi draws the room for every recording), with probability
// --isotropic-noise-addition-probability, one per recording, as background noise.
#include "augment/noise_type.h"
#include "util/cli.h"
#include "util/error.h"

namespace tsrir {
namespace {

class IsotropicNoise : public NoiseType {
 public:
  std::string name() const override { return "isotropic"; }

  void check(const NoiseChoice& entry, const std::set<std::string>& rooms) const override {
    if (entry.room_linkage.empty()) throw Error(entry.where + ": isotropic noise needs --room-linkage");
    if (!rooms.count(entry.room_linkage))
      log_warning(entry.where + ": isotropic noise '" + entry.id + "' is linked to room '" + entry.room_linkage +
                  "', which no --rir-set-parameters list contains: it is never used (as in Kaldi)");
    if (entry.bg_fg_type == BgFgType::kForeground)
      log_warning(entry.where + ": isotropic noises are always added as background noise (as in Kaldi)");
  }

  // Kaldi: per room, the given --probability values with the rest shared equally, normalised; set
  // weights and smoothing do not apply to isotropic noises.
  void assign_probabilities(const std::vector<NoiseChoice*>& entries, const std::vector<double>&,
                            double) const override {
    std::map<std::string, std::vector<NoiseChoice*>> by_room;
    for (NoiseChoice* n : entries) by_room[n->room_linkage].push_back(n);
    for (auto& [room, noises] : by_room) {
      std::vector<std::optional<double>> given;
      for (NoiseChoice* n : noises) given.push_back(n->given_probability);
      std::vector<double> p = kaldi_smoothed_probabilities(given, 0.0, 1.0, "isotropic noises of room '" + room + "'");
      for (size_t i = 0; i < noises.size(); ++i) noises[i]->probability = p[i];
    }
  }

  void plan(const NoisePlanContext& context, std::vector<PlannedNoise>* out) const override {
    if (context.room.empty()) return;
    std::vector<size_t> candidates;
    for (size_t i : context.sources.noises_of_type(name()))
      if (context.sources.noises[i].room_linkage == context.room) candidates.push_back(i);
    if (candidates.empty()) return;
    if (!(context.rng.uniform() < context.options.isotropic_noise_addition_probability)) return;
    const size_t noise = draw_noise(context.sources, candidates, context.rng.uniform());
    out->push_back(background_noise(context, noise, -1));
  }
};

}  // namespace

std::unique_ptr<NoiseType> make_isotropic_noise_type() { return std::make_unique<IsotropicNoise>(); }

}  // namespace tsrir
