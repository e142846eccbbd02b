// band_absorption: some band of some room decays faster or slower than its stated absorption gives
// (the absorption prior is wrong per band: panels, furniture, people).
//   Statistic  per-room, per-band mean log decay-rate ratio ln(rate_measured / rate_simulated),
//              less the share a room-size error explains (the room's mean change over the bands,
//              clamped to what a 5 % size error gives: it changes every band alike), t-tested per
//              band and room (Bonferroni over rooms x bands). When air_absorption is
//              detected, the residual after the air curve is tested; otherwise the raw ratio, and
//              the refit then also absorbs air's share (decay_rate_effects.h).
//   Depends    room_modes: bands below twice the Schroeder frequency are left to it when it is
//              detected, unless they decay faster than simulated (one-sided: less damped modes
//              only slow the decay, and the modes' fitted decay_scale explains a slower one; a
//              faster one is absorption beyond the fitted modes, and is refitted here);
//              air_absorption: its curve is removed first when detected (decision and fit).
//   Extension  sim "band_absorption" (src/sim/room_refits.h), per room: factors on the absorption
//              exponent -ln(1 - a) (Eyring: the decay rate is proportional to it) from the median
//              measured / simulated decay rate, air's share removed, then refined by analysis by
//              synthesis (decay_rate_effects.h: refine_band_scales).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "diagnose/decay_rate_effects.h"
#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"
#include "sim/room_refits.h"

namespace tsrir::diagnose {
namespace {

// ", faster: 125 Hz, 250 Hz" (the low bands that decay faster than simulated), or nothing.
std::string low_bands_note(const std::vector<int>& bands) {
  std::string out;
  for (int b : bands) {
    const std::string name = band_name(b);
    if (out.find(name) == std::string::npos) out += (out.empty() ? " (faster: " : ", ") + name;
  }
  return out.empty() ? out : out + ")";
}

class BandAbsorptionEffect : public Effect {
 public:
  std::string name() const override { return "band_absorption"; }
  std::string description() const override {
    return "a band of a room decays faster or slower than its stated absorption gives: per-band, per-room decay-rate "
           "ratios (after the air curve when air_absorption is detected); extension: band_absorption per room "
           "(factors on -ln(1 - a)).";
  }
  std::vector<Threshold> thresholds() const override { return kBandThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kT30PerBand); }
  std::vector<ResidualView> residual_views() const override { return {ResidualView::kDecayShape, ResidualView::kTwoSlopes, ResidualView::kLatePeriodicity}; }
  bool within_band_refit() const override { return true; }
  std::vector<std::string> depends_on() const override { return {"room_modes", "air_absorption"}; }

  Finding detect(const DecisionContext& ctx) const override {
    const SetObservations& obs = ctx.obs();
    const size_t n = obs.size();
    const DecayRateAnalysis a = analyse_decay_rates(obs, ctx.detected("room_modes"));
    const double min_ratio = std::log(kBandThresholds.min_rate_ratio);
    const double wr = a.measured.worst_ratio, wrn = a.null.worst_ratio;
    Finding band;
    band.effect = name();
    band.detected = a.measured.band_fires && !a.null.band_fires;
    band.statistic = wr;
    band.null_statistic = wrn;
    band.threshold = min_ratio;
    band.statistic_unit = "ln(rate ratio)";
    band.confidence = confidence_of(std::isfinite(wr) ? student_t_two_sided_p(a.t_crit, n - 1.0) : 1.0, wr, min_ratio,
                                    band.detected);
    band.evidence = "largest per-band decay-rate departure " + num(100.0 * std::expm1(wr), 2) + "%" +
                    (a.measured.worst_band >= 0 ? " at " + band_name(a.measured.worst_band) : std::string()) +
                    (a.num_rooms > 1 ? " in room " + a.measured.worst_room : std::string()) + " (threshold " +
                    num(100.0 * (kBandThresholds.min_rate_ratio - 1.0)) + "% at |t| > " + num(a.t_crit) +
                    ", beyond a uniform change of up to " + num(100.0 * (1.0 / (1.0 - kBandThresholds.max_size_error) - 1.0), 2) +
                    "% for a room-size error" +
                    (ctx.detected("air_absorption") ? ", after the air-absorption fit" : "") + ")" +
                    (a.low_bands_left_to_modes ? "; bands below " + num(2.0 * a.schroeder_hz) +
                                                     " Hz are left to room_modes unless they decay faster than simulated" +
                                                     low_bands_note(a.measured.low_faster_bands)
                                               : "") +
                    "; seed-vs-seed largest " + num(100.0 * std::expm1(wrn), 2) + "%.";
    // The report's band-level plot: level re broadband, measured - simulated, every band.
    std::vector<double>& mean = band.curves["mean_level_delta_db"];
    std::vector<double>& se = band.curves["se_level_delta_db"];
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const OneSampleTest l = t_test(measured_minus_sim(obs, [b](const RirFeatures& f) { return f.level_db[b]; }));
      mean.push_back(l.n ? l.mean : NAN);
      se.push_back(l.n ? l.standard_error : NAN);
    }
    return band;
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    AirFit air_fit;
    if (ctx.detected("air_absorption")) {
      for (const auto& [k, v] : ctx.finding("air_absorption").parameters) {
        if (k == "humidity_percent") air_fit.humidity_percent = v;
        if (k == "scale") air_fit.scale = v;
      }
    }
    const std::string air_spec = air_fit.scale > 0.0 ? "+air:humidity=" + spec_num(air_fit.humidity_percent) +
                                                           ",scale=" + spec_num(air_fit.scale)
                                                     : std::string();
    const bool modes = ctx.detected("room_modes");
    const double keep_below = modes ? 2.0 * median_of(obs.each([](const RirObservation& r) { return r.schroeder_hz; })) : 0.0;
    // The low bands that decay faster than the modes can explain (decided on the fit half) take
    // their median rate ratio; refine_band_scales leaves them as they are (its renders have no modes).
    const std::vector<int> low_faster =
        modes ? analyse_decay_rates(obs.subset(ctx.fit_index()), true).measured.low_faster_bands : std::vector<int>{};
    Extension ext;
    finding->parameters.clear();
    for (const auto& [room, idx] : ctx.fit_by_room()) {
      sim::BandValues start = band_absorption_scales(obs, idx, air_fit, keep_below);
      const sim::BandValues all_bands = band_absorption_scales(obs, idx, air_fit, 0.0);
      for (int b : low_faster) start[b] = std::max(1.0, all_bands[b]);
      const sim::BandValues scale =
          refine_band_scales(obs, idx, start, ctx.options().baseline_model + air_spec, ctx.options(), 3, keep_below);
      for (int b = 0; b < kNumOctaveBands; ++b) {
        finding->parameters.push_back(
            {(ctx.fit_by_room().size() > 1 ? room + "." : std::string()) + sim::band_absorption_key(b), scale[b]});
      }
      ext.by_room[room] = "+" + band_absorption_spec(scale);
    }
    return ext;
  }

  void report_set(const Finding& f, const Diagnosis&, std::ostream& html) const override {
    PlotSpec p = octave_band_plot("Band level (re broadband), measured - simulated", "dB");
    Series s{"mean +- 2 s.e.", "#1f77b4", octave_band_axis(), f.curves.at("mean_level_delta_db")};
    s.points = true;
    for (double v : f.curves.at("se_level_delta_db")) s.y_error.push_back(2.0 * v);
    const Series zero = octave_band_zero_line();
    finite_range({s.y, {2.0, -2.0}}, &p.y_min, &p.y_max, 1.0);
    p.series = {zero, s};
    html << svg_plot(p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_band_absorption_effect() { return std::make_unique<BandAbsorptionEffect>(); }

}  // namespace tsrir::diagnose
