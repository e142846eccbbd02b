#include "augment/augment_sources.h"

#include <map>
#include <optional>
#include <set>

#include "augment/sampling.h"
#include "io/kaldi_lists.h"
#include "util/cli.h"
#include "util/error.h"

namespace tsrir {

std::vector<size_t> AugmentSources::noises_for_room(const std::string& room_id) const {
  std::vector<size_t> out;
  for (size_t i = 0; i < noises.size(); ++i) {
    const NoiseChoice& n = noises[i];
    if (n.noise_type == "isotropic" ? (!room_id.empty() && n.room_linkage == room_id) : true) out.push_back(i);
  }
  return out;
}

AugmentSources load_augment_sources(const std::vector<std::string>& rir_set_parameters,
                                    const std::vector<std::string>& noise_set_parameters,
                                    double rir_smoothing_weight, double noise_smoothing_weight) {
  AugmentSources sources;

  std::vector<SetParameters> rir_sets;
  std::vector<std::optional<double>> rir_weights;
  for (const std::string& text : rir_set_parameters) {
    rir_sets.push_back(parse_set_parameters(text, "--rir-set-parameters"));
    rir_weights.push_back(rir_sets.back().weight);
  }
  std::vector<double> rir_set_weight;
  if (!rir_sets.empty()) rir_set_weight = resolve_set_weights(rir_weights, "--rir-set-parameters");
  std::map<std::string, std::string> rir_seen;  // id -> where
  std::set<std::string> rooms;
  for (size_t s = 0; s < rir_sets.size(); ++s) {
    const std::string& path = rir_sets[s].path;
    std::vector<RirListEntry> entries = read_rir_list(path);
    if (entries.empty()) throw Error(path + ": RIR list is empty");
    std::vector<std::optional<double>> given;
    for (const auto& e : entries) given.push_back(e.probability);
    std::vector<double> p = item_probabilities(given, rir_smoothing_weight, path);
    for (size_t i = 0; i < entries.size(); ++i) {
      const RirListEntry& e = entries[i];
      RirChoice c;
      c.id = e.rir_id;
      c.room_id = e.room_id.empty() ? e.rir_id : e.room_id;
      c.rxfilename = e.rxfilename;
      c.where = path + ":" + std::to_string(e.line);
      c.probability = p[i] * rir_set_weight[s];
      auto [it, inserted] = rir_seen.emplace(c.id, c.where);
      if (!inserted) throw Error(located(path, e.line, "RIR id '" + c.id + "' already listed at " + it->second));
      rooms.insert(c.room_id);
      sources.rirs.push_back(std::move(c));
    }
  }

  std::vector<SetParameters> noise_sets;
  std::vector<std::optional<double>> noise_weights;
  for (const std::string& text : noise_set_parameters) {
    noise_sets.push_back(parse_set_parameters(text, "--noise-set-parameters"));
    noise_weights.push_back(noise_sets.back().weight);
  }
  std::vector<double> noise_set_weight;
  if (!noise_sets.empty()) noise_set_weight = resolve_set_weights(noise_weights, "--noise-set-parameters");
  std::map<std::string, std::string> noise_seen;
  bool warned_foreground = false;
  for (size_t s = 0; s < noise_sets.size(); ++s) {
    const std::string& path = noise_sets[s].path;
    std::vector<NoiseListEntry> entries = read_noise_list(path);
    if (entries.empty()) throw Error(path + ": noise list is empty");
    std::vector<std::optional<double>> given;
    for (const auto& e : entries) given.push_back(e.probability);
    std::vector<double> p = item_probabilities(given, noise_smoothing_weight, path);
    for (size_t i = 0; i < entries.size(); ++i) {
      const NoiseListEntry& e = entries[i];
      if (e.noise_type == "isotropic" && !rooms.count(e.room_linkage))
        throw Error(located(path, e.line, "isotropic noise '" + e.noise_id + "' is linked to room '" + e.room_linkage +
                                              "', which no --rir-set-parameters list contains"));
      if (e.bg_fg_type == "foreground" && !warned_foreground) {
        log_warning(located(path, e.line, "foreground noises are added like background noise (looped from a random "
                                          "offset over the whole utterance)"));
        warned_foreground = true;
      }
      NoiseChoice c;
      c.id = e.noise_id;
      c.noise_type = e.noise_type;
      c.room_linkage = e.room_linkage;
      c.rxfilename = e.rxfilename;
      c.where = path + ":" + std::to_string(e.line);
      c.probability = p[i] * noise_set_weight[s];
      auto [it, inserted] = noise_seen.emplace(c.id, c.where);
      if (!inserted) throw Error(located(path, e.line, "noise id '" + c.id + "' already listed at " + it->second));
      sources.noises.push_back(std::move(c));
    }
  }
  return sources;
}

}  // namespace tsrir
