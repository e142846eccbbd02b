// The statistical rules the effects' detectors share (effect.h): paired differences over the set,
// a mean rule calibrated on the seed-vs-seed null, confidences and the text of the evidence.
#pragma once
#include <string>
#include <vector>

#include "diagnose/effect.h"
#include "diagnose/set_statistics.h"

namespace tsrir::diagnose {

// A number as the evidence and the summary print it ("n/a" when not finite).
std::string num(double v, int digits = 3);
std::string band_name(int band);  // "1000 Hz"

// Critical |t| for a two-sided p at dof degrees of freedom (bisection on the exact tail).
double t_critical(double p, double dof);

// In [0.5, 1] when detected, [0, 0.49] otherwise: (1 - p) x the effect size re its threshold.
double confidence_of(double p, double effect, double threshold, bool detected);

// A statistic's paired differences, f(measured) - f(seed A) per RIR.
template <typename F>
std::vector<double> measured_minus_sim(const SetObservations& obs, F f) {
  return obs.each([&](const RirObservation& r) { return f(r.meas) - f(r.sim_a); });
}
// Its null calibration, f(seed B) - f(seed A) per RIR.
template <typename F>
std::vector<double> seed_b_minus_a(const SetObservations& obs, F f) {
  return obs.each([&](const RirObservation& r) { return f(r.sim_b) - f(r.sim_a); });
}

// A paired-mean rule: fires when the mean of d is beyond min_effect in the given direction (+1,
// -1, 0 = both) at p < alpha over at least 3 RIRs.
struct MeanDecision {
  bool fires = false;
  OneSampleTest test;
};
MeanDecision mean_rule(const std::vector<double>& d, double min_effect, int sign);

// A finding decided by mean_rule on d (measured - sim A), calibrated on e (sim B - sim A): detected
// when d fires and e does not. `what` and `unit` name the statistic in the evidence.
Finding decide_mean(const std::string& effect, const std::vector<double>& d, const std::vector<double>& e,
                    double min_effect, int sign, const std::string& what, const std::string& unit);

}  // namespace tsrir::diagnose
