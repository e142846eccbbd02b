// The random choices of reverberate-data: weighted RIR/noise sets with Kaldi's probability rules
// (reverberate_data_dir.py) and SNR specifications. Draws come from a per-utterance tsrir::Rng,
// so results are statistically equivalent to Kaldi's script (not bit-identical to its MT19937
// sequence) and never depend on the thread count.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "util/rng.h"

namespace tsrir {

// "--rir-set-parameters" / "--noise-set-parameters" value: "[<weight>,] <list-file>".
struct SetParameters {
  std::optional<double> weight;
  std::string path;
};
SetParameters parse_set_parameters(const std::string& text, const std::string& option);

// Final weight of each set: given weights as given; sets without one share 1 - sum(given)
// equally (Kaldi). Throws when the given weights exceed 1 or everything ends up zero.
std::vector<double> resolve_set_weights(const std::vector<std::optional<double>>& weights,
                                        const std::string& option);

// Probabilities of the items of one list, summing to 1: items with --probability keep it, the
// others share the remaining mass equally; then smoothed towards uniform,
// p <- (1 - w) p + w / n (Kaldi's --rir-smoothing-weight / --noise-smoothing-weight).
std::vector<double> item_probabilities(const std::vector<std::optional<double>>& given,
                                       double smoothing_weight, const std::string& context);

// Index drawn with probability weights[i] / sum(weights); u in [0, 1).
size_t weighted_index(const std::vector<double>& weights, double u);

// An SNR specification: "lo:hi" = uniform in [lo, hi) dB; "a,b,c" = one of the values, each
// equally likely; "x" = always x.
class SnrSpec {
 public:
  static SnrSpec parse(const std::string& text, const std::string& option);
  double draw(Rng& rng) const;
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  bool is_range_ = false;
  double lo_ = 0, hi_ = 0;
  std::vector<double> values_;
};

}  // namespace tsrir
