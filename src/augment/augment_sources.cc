#include "augment/augment_sources.h"

#include <set>

#include "augment/noise_type.h"
#include "augment/sampling.h"
#include "io/kaldi_lists.h"
#include "util/cli.h"
#include "util/error.h"

namespace tsrir {

std::vector<size_t> AugmentSources::noises_of_type(const std::string& type) const {
  std::vector<size_t> out;
  for (size_t i = 0; i < noises.size(); ++i)
    if (noises[i].noise_type == type) out.push_back(i);
  return out;
}

namespace {

std::vector<double> set_weights(const std::vector<std::string>& texts, const std::string& option,
                                std::vector<SetParameters>* sets) {
  std::vector<std::optional<double>> weights;
  for (const std::string& text : texts) {
    sets->push_back(parse_set_parameters(text, option));
    weights.push_back(sets->back().weight);
  }
  if (sets->empty()) return {};
  return resolve_set_weights(weights, option);
}

void warn_duplicate(std::map<std::string, std::string>* seen, const std::string& kind, const std::string& id,
                    const std::string& where) {
  auto [it, inserted] = seen->emplace(id, where);
  if (!inserted)
    log_warning(where + ": " + kind + " id '" + id + "' already listed at " + it->second +
                " (accepted as Kaldi does; both entries are kept and drawn separately)");
}

}  // namespace

AugmentSources load_augment_sources(const std::vector<std::string>& rir_set_parameters,
                                    const std::vector<std::string>& noise_set_parameters,
                                    double rir_smoothing_weight, double noise_smoothing_weight) {
  AugmentSources sources;

  std::vector<SetParameters> rir_sets;
  const std::vector<double> rir_set_weight = set_weights(rir_set_parameters, "--rir-set-parameters", &rir_sets);
  std::map<std::string, std::string> rir_seen;  // id -> where
  for (size_t s = 0; s < rir_sets.size(); ++s) {
    const std::string& path = rir_sets[s].path;
    std::vector<RirListEntry> entries = read_rir_list(path);
    std::vector<std::optional<double>> given;
    for (const auto& e : entries) given.push_back(e.probability);
    std::vector<double> p = kaldi_smoothed_probabilities(given, rir_smoothing_weight, rir_set_weight[s], path);
    for (size_t i = 0; i < entries.size(); ++i) {
      const RirListEntry& e = entries[i];
      RirChoice c;
      c.id = e.rir_id;
      c.room_id = e.room_id.empty() ? e.rir_id : e.room_id;
      c.rxfilename = e.rxfilename;
      c.where = path + ":" + std::to_string(e.line);
      c.probability = p[i];
      warn_duplicate(&rir_seen, "RIR", c.id, c.where);
      sources.rirs_by_room[c.room_id].push_back(sources.rirs.size());
      sources.rirs.push_back(std::move(c));
    }
  }
  std::set<std::string> rooms;
  for (const auto& [room, indices] : sources.rirs_by_room) rooms.insert(room);

  std::vector<SetParameters> noise_sets;
  sources.noise_set_weights = set_weights(noise_set_parameters, "--noise-set-parameters", &noise_sets);
  std::map<std::string, std::string> noise_seen;
  for (size_t s = 0; s < noise_sets.size(); ++s) {
    const std::string& path = noise_sets[s].path;
    std::vector<NoiseListEntry> entries = read_noise_list(path);
    if (entries.empty()) log_warning(path + ": the noise list is empty; no noise is added from it (as in Kaldi)");
    for (const NoiseListEntry& e : entries) {
      NoiseChoice c;
      c.id = e.noise_id;
      c.noise_type = e.noise_type;
      c.bg_fg_type = e.bg_fg_type;
      c.room_linkage = e.room_linkage;
      c.rxfilename = e.rxfilename;
      c.where = path + ":" + std::to_string(e.line);
      c.set = s;
      c.given_probability = e.probability;
      const NoiseType* type = find_noise_type(c.noise_type);
      if (!type) {
        std::string known;
        for (const auto& t : noise_types()) known += (known.empty() ? "" : ", ") + t->name();
        throw Error(c.where + ": unknown --noise-type '" + c.noise_type + "' (known: " + known + ")");
      }
      type->check(c, rooms);
      warn_duplicate(&noise_seen, "noise", c.id, c.where);
      sources.noises.push_back(std::move(c));
    }
  }
  for (const auto& type : noise_types()) {
    std::vector<NoiseChoice*> of_type;
    for (NoiseChoice& n : sources.noises)
      if (n.noise_type == type->name()) of_type.push_back(&n);
    if (!of_type.empty()) type->assign_probabilities(of_type, sources.noise_set_weights, noise_smoothing_weight);
  }
  return sources;
}

}  // namespace tsrir
