#include "diagnose/decision_rules.h"

#include <algorithm>
#include <cmath>

#include "util/strings.h"

namespace tsrir::diagnose {

std::string num(double v, int digits) { return std::isfinite(v) ? format_double(v, digits) : "n/a"; }

std::string band_name(int b) { return octave_band_label(kOctaveCentersHz[b]) + " Hz"; }

double t_critical(double p, double dof) {
  double lo = 0.0, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_two_sided_p(mid, dof) > p ? lo : hi) = mid;
  }
  return hi;
}

double confidence_of(double p, double effect, double threshold, bool detected) {
  double c = std::clamp(1.0 - p, 0.0, 1.0) * std::clamp(std::abs(effect) / threshold, 0.0, 1.0);
  if (!std::isfinite(c)) c = 0.0;
  return detected ? std::max(c, 0.5) : std::min(c, 0.49);
}

MeanDecision mean_rule(const std::vector<double>& d, double min_effect, int sign) {
  MeanDecision r;
  r.test = t_test(d);
  const bool direction_ok = sign == 0 || (sign > 0 ? r.test.mean > 0 : r.test.mean < 0);
  r.fires = r.test.n >= 3 && direction_ok && std::abs(r.test.mean) > min_effect && r.test.p_two_sided < kDecision.alpha;
  return r;
}

Finding decide_mean(const std::string& effect, const std::vector<double>& d, const std::vector<double>& e,
                    double min_effect, int sign, const std::string& what, const std::string& unit) {
  Finding f;
  f.effect = effect;
  const MeanDecision m = mean_rule(d, min_effect, sign);
  const MeanDecision null = mean_rule(e, min_effect, sign);
  f.statistic = m.test.mean;
  f.null_statistic = null.test.mean;
  f.threshold = min_effect;
  f.statistic_unit = unit;
  f.detected = m.fires && !null.fires;
  f.confidence = confidence_of(m.test.p_two_sided, m.test.mean, min_effect, f.detected);
  f.evidence = what + ": measured - simulated = " + num(m.test.mean) + " +- " + num(m.test.standard_error) + " " + unit +
               " over " + std::to_string(m.test.n) + " RIRs (t = " + num(m.test.t) + ", p = " + num(m.test.p_two_sided, 2) +
               "; threshold " + num(min_effect) + " " + unit + " at p < " + num(kDecision.alpha) + "); seed-vs-seed " +
               num(null.test.mean) + " " + unit + (null.fires ? " (null also fires: statistic not trusted)" : "") + ".";
  return f;
}

}  // namespace tsrir::diagnose
