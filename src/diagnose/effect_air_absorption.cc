// air_absorption: the air absorbs more (or less) than the stated temperature and humidity give;
// it speeds up the decay of the high bands by ISO 9613-1's curve.
//   Statistic  per-room, per-band mean log decay-rate ratios ln(rate_measured / rate_simulated)
//              fitted by one ISO 9613-1 band decay increase for all rooms (humidity and scale
//              fitted, decay_rate_effects.h): the fit must remove most of the chi-square, improve
//              it over no change AND over one uniform rate factor for all bands, leave no room's
//              band significant, and predict a clearly faster decay in the top band. The rule
//              against band_absorption lives in decay_rate_effects.h (air only when one curve
//              explains everything).
//   Depends    room_modes: its bands (below twice the Schroeder frequency) are left out when it is
//              detected.
//   Extension  sim "air" (src/sim/air_absorption.h): humidity and scale refitted on the fit RIRs.
#include <cmath>

#include "diagnose/decay_rate_effects.h"
#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"

namespace tsrir::diagnose {
namespace {

std::vector<double> percent(const std::vector<double>& log_ratio) {
  std::vector<double> out;
  for (double v : log_ratio) out.push_back(std::isfinite(v) ? 100.0 * std::expm1(v) : NAN);
  return out;
}

class AirAbsorptionEffect : public Effect {
 public:
  std::string name() const override { return "air_absorption"; }
  std::string description() const override {
    return "the air's absorption differs from the stated temperature/humidity: per-band decay-rate ratios explained "
           "by one ISO 9613-1 curve for all rooms; extension: air (humidity, scale).";
  }
  std::vector<Threshold> thresholds() const override { return kAirThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kT30PerBand); }
  std::vector<ResidualView> residual_views() const override { return {ResidualView::kDecayShape, ResidualView::kTwoSlopes, ResidualView::kLatePeriodicity}; }
  bool within_band_refit() const override { return true; }
  std::vector<std::string> depends_on() const override { return {"room_modes"}; }

  Finding detect(const DecisionContext& ctx) const override {
    const SetObservations& obs = ctx.obs();
    const DecayRateAnalysis a = analyse_decay_rates(obs, ctx.detected("room_modes"));
    const AirFit& fit = a.measured.fit;
    Finding air;
    air.effect = name();
    air.detected = a.measured.air_fires && !a.null.air_fires;
    const double top_air = a.tested.empty() ? 0.0 : a.measured.air_curve[a.tested.back()];
    const double min_top = std::log(kAirThresholds.min_top_rate_ratio);
    air.statistic = top_air;
    air.null_statistic = a.tested.empty() ? 0.0 : a.null.air_curve[a.tested.back()];
    air.threshold = min_top;
    air.statistic_unit = "ln(rate ratio)";
    const double p_air = chi_square_upper_p(std::max(0.0, fit.chi2_zero - fit.chi2_fit), 2.0);
    air.confidence = confidence_of(p_air, top_air, min_top, air.detected);
    std::string per_band;
    for (int b : a.tested) {
      per_band += (per_band.empty() ? "" : ", ") + band_name(b) + " " + num(100.0 * std::expm1(mean_of(a.q[b])), 2) + "%";
    }
    air.evidence = "decay-rate change per band (measured vs simulated): " + per_band +
                   "; the best ISO 9613-1 curve (humidity " + num(fit.humidity_percent) + " %, scale " + num(fit.scale) +
                   ") reduces chi-square from " + num(fit.chi2_zero) + " to " + num(fit.chi2_fit) +
                   " (one uniform rate factor for all bands: " + num(a.measured.uniform_chi2) + ")" + " and predicts " +
                   num(100.0 * std::expm1(top_air), 2) + "% faster decay in the top band (needs > " +
                   num(100.0 * (kAirThresholds.min_top_rate_ratio - 1.0)) + "%, < " +
                   num(100.0 * kAirThresholds.max_chi2_fraction) + "% of chi-square left, " +
                   num(kAirThresholds.min_chi2_improvement) +
                   " below the uniform factor's, and no significant residual band).";
    if (air.detected) air.parameters = {{"humidity_percent", fit.humidity_percent}, {"scale", fit.scale}};
    // The report's decay-rate plot: all bands, the fitted curve on the tested ones.
    std::vector<double>& mean = air.curves["mean_log_rate_ratio"];
    std::vector<double>& se = air.curves["se_log_rate_ratio"];
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const OneSampleTest t = t_test(a.q[b]);
      mean.push_back(t.n ? t.mean : NAN);
      se.push_back(t.n ? t.standard_error : NAN);
    }
    air.curves["air_fit_log_ratio"].assign(a.measured.air_curve.begin(), a.measured.air_curve.end());
    return air;
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    const double temp = obs[0].room.temperature_c, c = obs[0].room.speed_of_sound_m_s;
    // Humidity and scale refitted on the fit part only.
    std::vector<RateObservation> observations;
    for (const auto& [room, idx] : ctx.fit_by_room()) {
      for (int b = 0; b < kNumOctaveBands; ++b) {
        std::vector<double> q, r;
        for (size_t i : idx) {
          q.push_back(std::log(obs[i].meas.decay_rate_per_s[b] / obs[i].sim_a.decay_rate_per_s[b]));
          r.push_back(obs[i].sim_a.decay_rate_per_s[b]);
        }
        const OneSampleTest t = t_test(q);
        if (t.n >= 3 && t.n >= 0.8 * idx.size()) {
          observations.push_back({b, t.mean, std::max(t.standard_error, 1e-4), median_of(r)});
        }
      }
    }
    const AirFit fit = fit_air(observations, temp, c);
    finding->parameters = {{"humidity_percent", fit.humidity_percent}, {"scale", fit.scale}};
    return {"+air:humidity=" + spec_num(fit.humidity_percent) + ",scale=" + spec_num(fit.scale), {}};
  }

  void report_set(const Finding& f, const Diagnosis&, std::ostream& html) const override {
    const std::vector<double>& mean = f.curves.at("mean_log_rate_ratio");
    const std::vector<double>& se = f.curves.at("se_log_rate_ratio");
    PlotSpec p = octave_band_plot("Decay rate, measured vs simulated (T30)", "rate change, % (+ = decays faster)");
    Series s{"measured/simulated", "#1f77b4", octave_band_axis(), percent(mean)};
    s.points = true;
    for (int b = 0; b < kNumOctaveBands; ++b) s.y_error.push_back(100.0 * std::exp(mean[b]) * se[b] * 2.0);
    Series air{"air fit", "#2ca02c", octave_band_axis(), percent(f.curves.at("air_fit_log_ratio"))};
    air.dashed = true;
    const Series zero = octave_band_zero_line();
    finite_range({s.y, {0.0, 10.0, -10.0}}, &p.y_min, &p.y_max, 5.0);
    p.series = {zero, s, air};
    html << svg_plot(p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_air_absorption_effect() { return std::make_unique<AirAbsorptionEffect>(); }

}  // namespace tsrir::diagnose
