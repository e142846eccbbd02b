// The RIRs and noises reverberate-data draws from: Kaldi rir_list / noise_list files (or scps),
// each with a set weight, flattened into one weighted list of RIRs (grouped by room) and one list
// of noises whose probabilities each noise type (noise_type.h) assigns by Kaldi's rules.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/kaldi_lists.h"

namespace tsrir {

struct RirChoice {
  std::string id;
  std::string room_id;
  std::string rxfilename;
  std::string where;          // "list:line" for messages
  double probability = 0.0;   // over all RIRs of all sets (sums to 1)
};

struct NoiseChoice {
  std::string id;
  std::string noise_type;     // a registered noise type: "isotropic" | "point-source"
  BgFgType bg_fg_type = BgFgType::kBackground;
  std::string room_linkage;   // isotropic noises: the room they were recorded in
  std::string rxfilename;
  std::string where;
  size_t set = 0;                          // index of its --noise-set-parameters
  std::optional<double> given_probability; // --probability in the list
  double probability = 0.0;   // set by its noise type (within the group it is drawn from)
};

struct AugmentSources {
  std::vector<RirChoice> rirs;
  std::vector<NoiseChoice> noises;
  std::vector<double> noise_set_weights;
  std::map<std::string, std::vector<size_t>> rirs_by_room;  // room id -> indices into rirs
  // Indices of the noises of one type.
  std::vector<size_t> noises_of_type(const std::string& type) const;
};

// Reads the sets ("[weight,] list" each). The same RIR or noise id in two lists (or a list given
// twice) is accepted as in Kaldi, with a warning: the entries stay apart (indices, not ids, identify
// them). An empty noise list adds nothing (Kaldi); an empty RIR list is an error. Errors name the
// list file and line.
AugmentSources load_augment_sources(const std::vector<std::string>& rir_set_parameters,
                                    const std::vector<std::string>& noise_set_parameters,
                                    double rir_smoothing_weight, double noise_smoothing_weight);

}  // namespace tsrir
