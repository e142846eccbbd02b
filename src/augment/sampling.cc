#include "augment/sampling.h"

#include <cmath>

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

std::vector<double> resolve_set_weights(const std::vector<std::optional<double>>& weights,
                                        const std::string& option) {
  double given = 0.0;
  size_t missing = 0;
  for (const auto& w : weights) {
    if (w) given += *w;
    else ++missing;
  }
  if (given > 1.0 + 1e-6 && missing > 0)
    throw Error(option + ": the given weights sum to " + format_double(given) +
                " > 1, leaving nothing for the sets without a weight");
  std::vector<double> out;
  double total = 0.0;
  for (const auto& w : weights) {
    out.push_back(w ? *w : (1.0 - given) / static_cast<double>(missing));
    total += out.back();
  }
  if (!(total > 0)) throw Error(option + ": all set weights are zero");
  for (double& w : out) w /= total;
  return out;
}

std::vector<double> item_probabilities(const std::vector<std::optional<double>>& given,
                                       double smoothing_weight, const std::string& context) {
  if (given.empty()) throw Error(context + ": the list is empty");
  if (smoothing_weight < 0 || smoothing_weight > 1)
    throw Error("smoothing weight must be in [0, 1], got " + format_double(smoothing_weight));
  double specified = 0.0;
  size_t missing = 0;
  for (const auto& p : given) {
    if (p) {
      if (*p < 0) throw Error(context + ": negative --probability");
      specified += *p;
    } else {
      ++missing;
    }
  }
  const double leftover = missing ? std::max(0.0, 1.0 - specified) / static_cast<double>(missing) : 0.0;
  std::vector<double> p;
  double total = 0.0;
  for (const auto& g : given) {
    p.push_back(g ? *g : leftover);
    total += p.back();
  }
  const double n = static_cast<double>(given.size());
  for (double& v : p) v = (1.0 - smoothing_weight) * (total > 0 ? v / total : 1.0 / n) + smoothing_weight / n;
  return p;
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
  if (spec.text_.find(':') != std::string::npos) {
    std::vector<std::string> parts = split(spec.text_, ':');
    if (parts.size() != 2)
      throw Error(option + " '" + text + "': a range is lo:hi; for a list of values use commas (20,10,0)");
    spec.is_range_ = true;
    spec.lo_ = parse_double(trim(parts[0]), option + " lower bound");
    spec.hi_ = parse_double(trim(parts[1]), option + " upper bound");
    if (spec.hi_ < spec.lo_) throw Error(option + " '" + text + "': upper bound below lower bound");
  } else {
    spec.values_ = parse_double_list(spec.text_, ',', option);
    if (spec.values_.empty()) throw Error(option + ": empty SNR list");
  }
  return spec;
}

double SnrSpec::draw(Rng& rng) const {
  if (is_range_) return rng.uniform(lo_, hi_);
  return values_[static_cast<size_t>(rng.below(values_.size()))];
}

}  // namespace tsrir
