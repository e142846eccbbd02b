// The random choices of reverberate-data: weighted RIR/noise sets with the probability rules of
// Kaldi's steps/data/reverberate_data_dir.py (docs/kaldi-reverberation.md) and SNR lists. Choices
// come from a per-recording tsrir::Rng, SNR lists are walked in Kaldi's cyclic order: results are
// statistically equivalent to Kaldi's script (not bit-identical to its MT19937 sequence) and never
// depend on the thread count.
#pragma once
#include <cstddef>
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

// Kaldi's smooth_probability_distribution(items, smoothing_weight, target_sum): items without a
// probability share u = (1 - sum(given)) / #unspecified (0, with a warning, when the given ones
// reach 1); given ones become (1 - w) p + w u; all are then scaled to sum to target_sum. With
// every probability given, u = 0 and the smoothing only rescales (as in Kaldi). Throws when the
// result has zero total mass (Kaldi divides by zero there).
std::vector<double> kaldi_smoothed_probabilities(const std::vector<std::optional<double>>& given,
                                                 double smoothing_weight, double target_sum,
                                                 const std::string& context);

// Final weight of each set: kaldi_smoothed_probabilities(weights, 0, 1).
std::vector<double> resolve_set_weights(const std::vector<std::optional<double>>& weights,
                                        const std::string& option);

// Index drawn with probability weights[i] / sum(weights); u in [0, 1).
size_t weighted_index(const std::vector<double>& weights, double u);

// An SNR specification. Kaldi's form: "20:10:0" = a list of values, walked cyclically in an order
// shuffled once (--foreground-snrs / --background-snrs). tsrir's extension, spelt differently so
// that no Kaldi string changes meaning: "lo..hi" = uniform in [lo, hi) dB, drawn per noise.
class SnrSpec {
 public:
  static SnrSpec parse(const std::string& text, const std::string& option);
  bool is_range() const { return is_range_; }
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  const std::vector<double>& values() const { return values_; }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  bool is_range_ = false;
  double lo_ = 0, hi_ = 0;
  std::vector<double> values_;
};

// Kaldi's list_cyclic_iterator: the list shuffled once (from `shuffle_rng`), then value k of the
// run is list[k mod n]. A range draws from the caller's per-recording generator instead.
class SnrSequence {
 public:
  SnrSequence(SnrSpec spec, Rng shuffle_rng);
  double next(Rng& per_recording_rng);
  const SnrSpec& spec() const { return spec_; }

 private:
  SnrSpec spec_;
  std::vector<double> order_;
  size_t index_ = 0;
};

}  // namespace tsrir
