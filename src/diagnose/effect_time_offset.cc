// time_offset: the measured onset does not follow the stated time of flight: a constant system
// latency (sound card, loudspeaker), or files pre-aligned so that the direct sound sits at a fixed
// time whatever the distance.
//   Statistic  |onset_measured - onset_simulated| beyond max(min_ms, null_mads x the MAD of the
//              seed-vs-seed onset differences) in more RIRs than a per-RIR false-alarm rate of
//              rirs_rate explains (binomial p < alpha), and the median |difference| beyond the
//              same threshold.
//   Extension  sim "onset_shift" (src/sim/onset_shift.h): the slope of measured onset against
//              stated time of flight tells the two causes apart: slope >= 0.5 is a latency (median
//              onset difference), below it a pre-alignment (median onset minus the simulator's
//              own offset of the direct sound).
#include <algorithm>
#include <cmath>

#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"

namespace tsrir::diagnose {
namespace {

struct TimeOffsetThresholds {
  double min_ms = 0.6;
  double null_mads = 5.0;
  double rirs_rate = 0.05;
  std::vector<Threshold> list() const {
    return {{"min_ms", min_ms,
             "0.2 m of path: stated positions are rarely better than +-0.1 m per coordinate (up to 0.17 m in "
             "distance), and an offset smaller than that is indistinguishable from them"},
            {"null_mads", null_mads, "or this many median absolute deviations of the seed-vs-seed onset differences"},
            {"rirs_rate", rirs_rate, "per-RIR false-alarm rate the binomial test of the count is against"}};
  }
};
constexpr TimeOffsetThresholds kThresholds{};

class TimeOffsetEffect : public Effect {
 public:
  std::string name() const override { return "time_offset"; }
  std::string description() const override {
    return "the onsets do not follow the stated time of flight (a constant latency, or pre-aligned files): onset "
           "differences beyond a threshold in more RIRs than chance; extension: onset_shift (latency_ms or "
           "align_ms).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kOnset); }

  Finding detect(const DecisionContext& ctx) const override {
    const SetObservations& obs = ctx.obs();
    const size_t n = obs.size();
    Finding offset;
    offset.effect = name();
    const std::vector<double> d = measured_minus_sim(obs, [](const RirFeatures& f) { return f.onset_s * 1e3; });
    const std::vector<double> e = seed_b_minus_a(obs, [](const RirFeatures& f) { return f.onset_s * 1e3; });
    const double thr = std::max(kThresholds.min_ms, kThresholds.null_mads * median_abs_deviation(e));
    auto rule = [&](const std::vector<double>& x, size_t* k, double* p, double* med) {
      std::vector<double> a;
      *k = 0;
      for (double v : x) { a.push_back(std::abs(v)); *k += std::abs(v) > thr; }
      *p = binomial_upper_p(*k, x.size(), kThresholds.rirs_rate);
      *med = median_of(a);
      return *p < kDecision.alpha && *med > thr;
    };
    size_t k, kn;
    double p, pn, med, medn;
    const bool fires = rule(d, &k, &p, &med);
    const bool null_fires = rule(e, &kn, &pn, &medn);
    offset.detected = fires && !null_fires;
    offset.statistic = med;
    offset.null_statistic = medn;
    offset.threshold = thr;
    offset.statistic_unit = "ms";
    offset.confidence = confidence_of(p, med, thr, offset.detected);
    offset.evidence = "onset differs from the simulated time of flight by more than " + num(thr) + " ms in " +
                      std::to_string(k) + " of " + std::to_string(n) + " RIRs (median |difference| " + num(med) +
                      " ms, median signed " + num(median_of(d)) + " ms; binomial p = " + num(p, 2) + " against a " +
                      num(100.0 * kThresholds.rirs_rate) + " % per-RIR rate); seed-vs-seed median " + num(medn) + " ms.";
    return offset;
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    std::vector<double> x, y, latency, sim_extra;
    for (size_t i : ctx.fit_index()) {
      const double flight = obs[i].room.source_mic_distance_m() / obs[i].room.speed_of_sound_m_s;
      x.push_back(flight);
      y.push_back(obs[i].meas.onset_s);
      latency.push_back(obs[i].meas.onset_s - obs[i].sim_a.onset_s);
      sim_extra.push_back(obs[i].sim_a.onset_s - flight);
    }
    const double mx = mean_of(x), my = mean_of(y);
    double sxy = 0.0, sxx = 0.0;
    for (size_t k = 0; k < x.size(); ++k) { sxy += (x[k] - mx) * (y[k] - my); sxx += (x[k] - mx) * (x[k] - mx); }
    const double slope = sxx > 0 ? sxy / sxx : 1.0;
    if (slope < 0.5) {
      const double align_ms = 1e3 * (median_of(y) - median_of(sim_extra));
      finding->parameters = {{"onset_vs_flight_slope", slope}, {"align_ms", align_ms}};
      return {"+onset_shift:align_ms=" + spec_num(std::max(0.0, align_ms)), {}};
    }
    const double latency_ms = 1e3 * median_of(latency);
    finding->parameters = {{"onset_vs_flight_slope", slope}, {"latency_ms", latency_ms}};
    return {"+onset_shift:latency_ms=" + spec_num(latency_ms), {}};
  }

  void report_set(const Finding&, const Diagnosis& d, std::ostream& html) const override {
    PlotSpec p;
    p.title = "Onset vs time of flight";
    p.x_label = "stated distance / c, ms";
    p.y_label = "detected onset, ms";
    Series m{"measured", "#1f77b4", d.flight_ms, d.onset_meas_ms};
    m.points = true;
    Series s{"simulated", "#ff7f0e", d.flight_ms, d.onset_sim_ms};
    s.points = true;
    double lo, hi;
    finite_range({d.flight_ms}, &lo, &hi, 1.0);
    p.x_min = std::max(0.0, lo);
    p.x_max = hi;
    finite_range({d.onset_meas_ms, d.onset_sim_ms}, &p.y_min, &p.y_max, 1.0);
    p.y_min = std::max(0.0, p.y_min);
    p.series = {m, s};
    html << svg_plot(p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_time_offset_effect() { return std::make_unique<TimeOffsetEffect>(); }

}  // namespace tsrir::diagnose
