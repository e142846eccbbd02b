// The RIRs and noises reverberate-data draws from: Kaldi rir_list / noise_list files (or scps),
// each with a set weight, flattened into one weighted list of RIRs and one of noises.
#pragma once
#include <string>
#include <vector>

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
  std::string noise_type;     // "isotropic" | "point-source"
  std::string room_linkage;   // isotropic noises: the room they were recorded in
  std::string rxfilename;
  std::string where;
  double probability = 0.0;   // over all noises of all sets (sums to 1)
};

struct AugmentSources {
  std::vector<RirChoice> rirs;
  std::vector<NoiseChoice> noises;
  // Noises usable with an RIR of `room_id` ("" = not reverberated): isotropic noises linked to
  // that room and every point-source noise; their probabilities (not renormalised).
  std::vector<size_t> noises_for_room(const std::string& room_id) const;
};

// Reads the sets ("[weight,] list" each). Errors name the list file and line: an empty list, a
// duplicate RIR or noise id across sets, an isotropic noise linked to a room that no RIR list
// contains, weights that do not leave room for the unweighted sets.
AugmentSources load_augment_sources(const std::vector<std::string>& rir_set_parameters,
                                    const std::vector<std::string>& noise_set_parameters,
                                    double rir_smoothing_weight, double noise_smoothing_weight);

}  // namespace tsrir
