// reverberate-data's RIR and noise sets: "[weight,] list" parameters over Kaldi rir_list /
// noise_list files (src/augment/augment_sources.h). The input is split at NUL bytes into: the RIR
// list, the noise list, the text before the RIR list's path in its --rir-set-parameters value
// (e.g. "0.5, "), the same for the noise set (absent = no noise set), and the two smoothing
// weights. Invariants: the RIR and noise probabilities are each a distribution (in [0,1], sum 1),
// and every noise usable with a room is point-source or linked to that room.
#include <cmath>
#include <map>

#include "augment/augment_sources.h"
#include "fuzz_common.h"
#include "util/strings.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string rir_path = fuzz::scratch_path("rir_list");
  static const std::string noise_path = fuzz::scratch_path("noise_list");
  auto parts = split(fuzz::as_text(data, size), '\0');
  parts.resize(std::max<size_t>(parts.size(), 6));
  fuzz::write_file(rir_path, parts[0]);
  fuzz::write_file(noise_path, parts[1]);
  fuzz::expect_only_errors([&] {
    std::vector<std::string> rir_params = {parts[2] + rir_path};
    std::vector<std::string> noise_params;
    if (!parts[3].empty()) noise_params.push_back(parts[3] + noise_path);
    const double rir_smoothing = parts[4].empty() ? 0.3 : parse_double(parts[4], "rir smoothing");
    const double noise_smoothing = parts[5].empty() ? 0.3 : parse_double(parts[5], "noise smoothing");
    if (!(rir_smoothing >= 0 && rir_smoothing <= 1 && noise_smoothing >= 0 && noise_smoothing <= 1)) return;
    AugmentSources s = load_augment_sources(rir_params, noise_params, rir_smoothing, noise_smoothing);
    double total = 0;
    for (const auto& r : s.rirs) {
      FUZZ_CHECK(r.probability >= 0 && r.probability <= 1 + 1e-12, r.id);
      total += r.probability;
    }
    FUZZ_CHECK(!s.rirs.empty() && std::fabs(total - 1) < 1e-9, "RIR probabilities sum to " + std::to_string(total));
    // Each noise type draws from its own group: all point sources; the isotropic noises of one room.
    std::map<std::string, double> group_total;
    for (const auto& n : s.noises) {
      FUZZ_CHECK(n.probability >= 0 && n.probability <= 1 + 1e-12, n.id);
      group_total[n.noise_type == "isotropic" ? "room " + n.room_linkage : n.noise_type] += n.probability;
    }
    for (const auto& [group, sum] : group_total)
      FUZZ_CHECK(std::fabs(sum - 1) < 1e-9, group + ": noise probabilities sum to " + std::to_string(sum));
    for (const auto& [room, indices] : s.rirs_by_room)
      for (size_t i : indices) FUZZ_CHECK(i < s.rirs.size() && s.rirs[i].room_id == room, "room index");
  });
  return 0;
}
