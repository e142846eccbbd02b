#include "augment/sampling.h"

#include <cmath>
#include <utility>

#include "util/cli.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

SetParameters parse_set_parameters(const std::string& text, const std::string& option) {
  SetParameters out;
  const size_t comma = text.find(',');
  if (comma == std::string::npos) {
    out.path = trim(text);
  } else {
    out.weight = parse_double(trim(text.substr(0, comma)), option + " '" + text + "' weight");
    out.path = trim(text.substr(comma + 1));
    if (*out.weight < 0) throw Error(option + " '" + text + "': negative weight");
  }
  if (out.path.empty()) throw Error(option + " '" + text + "': no list file given");
  return out;
}

std::vector<double> kaldi_smoothed_probabilities(const std::vector<std::optional<double>>& given,
                                                 double smoothing_weight, double target_sum,
                                                 const std::string& context) {
  if (smoothing_weight < 0 || smoothing_weight > 1)
    throw Error("smoothing weight must be in [0, 1], got " + format_double(smoothing_weight));
  if (given.empty()) return {};
  double specified = 0.0;
  size_t missing = 0;
  for (const auto& p : given) {
    if (p) {
      if (*p < 0) throw Error(context + ": negative probability or weight");
      specified += *p;
    } else {
      ++missing;
    }
  }
  double uniform = 0.0;
  if (missing > 0 && specified < 1) {
    uniform = (1.0 - specified) / static_cast<double>(missing);
  } else if (missing > 0) {
    log_warning(context + ": the given probabilities sum to " + format_double(specified) +
                " >= 1; the items without one get probability zero (as in Kaldi)");
  }
  std::vector<double> p;
  double total = 0.0;
  for (const auto& g : given) {
    p.push_back(g ? (1.0 - smoothing_weight) * *g + smoothing_weight * uniform : uniform);
    total += p.back();
  }
  if (!(total > 0)) throw Error(context + ": all probabilities are zero");
  for (double& v : p) v = v / total * target_sum;
  return p;
}

std::vector<double> resolve_set_weights(const std::vector<std::optional<double>>& weights,
                                        const std::string& option) {
  return kaldi_smoothed_probabilities(weights, 0.0, 1.0, option);
}

size_t weighted_index(const std::vector<double>& weights, double u) {
  double total = 0.0;
  for (double w : weights) total += w;
  if (weights.empty() || !(total > 0)) throw Error("weighted choice among zero total weight");
  const double target = u * total;
  double acc = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    acc += weights[i];
    if (target < acc) return i;
  }
  // u close to 1 with rounding in the sum: the last item with positive weight.
  for (size_t i = weights.size(); i-- > 0;)
    if (weights[i] > 0) return i;
  return weights.size() - 1;
}

SnrSpec SnrSpec::parse(const std::string& text, const std::string& option) {
  SnrSpec spec;
  spec.text_ = trim(text);
  if (spec.text_.empty()) throw Error(option + ": empty SNR specification");
  const size_t dots = spec.text_.find("..");
  if (dots != std::string::npos) {
    spec.is_range_ = true;
    spec.lo_ = parse_double(trim(spec.text_.substr(0, dots)), option + " '" + text + "' lower bound");
    spec.hi_ = parse_double(trim(spec.text_.substr(dots + 2)), option + " '" + text + "' upper bound");
    if (spec.hi_ < spec.lo_) throw Error(option + " '" + text + "': upper bound below lower bound");
    return spec;
  }
  if (spec.text_.find(',') != std::string::npos)
    throw Error(option + " '" + text + "': Kaldi's SNR lists are ':'-separated (20:10:0); a range is lo..hi");
  spec.values_ = parse_double_list(spec.text_, ':', option);
  if (spec.values_.empty()) throw Error(option + ": empty SNR list");
  return spec;
}

SnrSequence::SnrSequence(SnrSpec spec, Rng shuffle_rng) : spec_(std::move(spec)), order_(spec_.values()) {
  // Fisher-Yates, as Python's random.shuffle (uniform over permutations).
  for (size_t i = order_.size(); i > 1; --i) std::swap(order_[i - 1], order_[shuffle_rng.below(i)]);
}

double SnrSequence::next(Rng& per_recording_rng) {
  if (spec_.is_range()) return per_recording_rng.uniform(spec_.lo(), spec_.hi());
  const double v = order_[index_];
  index_ = (index_ + 1) % order_.size();
  return v;
}

}  // namespace tsrir
