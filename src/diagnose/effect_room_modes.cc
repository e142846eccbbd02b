// room_modes: the low-frequency field is modal where the simulation's is not: stronger, less damped
// or more persistent modes than the geometric model's image sources (cut at the transition time)
// and noise tail give.
//   Statistic  late-field spectral persistence (rir_features.h): the correlation of the power
//              spectrum's fine structure (re its local mean over +-10 Hz) between consecutive 150 ms
//              windows from 150 ms after the onset, 30 Hz to twice the stated room's Schroeder
//              frequency; paired mean (measured - simulated) over the set, one-sided. A modal field
//              keeps its spectral peaks from window to window however dense its modes are, wherever
//              they lie (the true room's size need not be the stated one) and whether they decay
//              like the tail or more slowly; the simulation's noise tail and measurement noise are a
//              new draw in every window, and a smooth trend (a loudspeaker's roll-off, a per-band
//              decay change) divides out. It replaced the prominence of the spectrum at the stated
//              room's predicted modes, which a dense field or a 5 % size error defeats
//              (docs/results/diagnose_power.md).
//   Extension  sim "modes" (src/sim/room_modes.h): the modal sum crossed over with the geometric
//              part below the Schroeder frequency; decay_scale = median measured / simulated
//              decay time (T30, T20 where T30 is not measurable) of the bands below twice the
//              Schroeder frequency, at least 1 (a faster low band is band_absorption's), level_db
//              from one trial render of
//              the fit RIRs (energy share below the Schroeder frequency, measured / trial).
#include <algorithm>
#include <cmath>

#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"
#include "util/parallel.h"

namespace tsrir::diagnose {
namespace {

struct RoomModesThresholds {
  // Set from the statistic's null distribution, not tuned for power: over 30 independent
  // "measured" sets with nothing hidden (tests' generator, seeds 1001-1030, 24 fit RIRs each)
  // (docs/results/diagnose_power.md).
  double min_persistence = 0.07;
  std::vector<Threshold> list() const {
    return {{"min_persistence", min_persistence,
             "mean late-field spectral persistence above the simulation's (sets with nothing hidden: see "
             "docs/results/diagnose_power.md)"}};
  }
};
constexpr RoomModesThresholds kThresholds{};

Finding decide_modes(const SetObservations& obs) {
  std::vector<double> d, e;
  for (const RirObservation& r : obs) {
    const size_t pairs = persistence_pairs_in_span(r.meas);
    d.push_back(mean_persistence(r.meas, pairs) - mean_persistence(r.sim_a, pairs));
    e.push_back(mean_persistence(r.sim_b, pairs) - mean_persistence(r.sim_a, pairs));
  }
  return decide_mean("room_modes", d, e, kThresholds.min_persistence, +1,
                     "late-field spectral persistence (fine-structure correlation of consecutive 150 ms windows from "
                     "150 ms, 30 Hz to 2x the Schroeder frequency)",
                     "");
}

class RoomModesEffect : public Effect {
 public:
  std::string name() const override { return "room_modes"; }
  std::string description() const override {
    return "the low-frequency field is modal where the simulation's is not: the late spectrum's fine structure "
           "persists from one 150 ms window to the next (a mode rings at its own frequency; noise is a new draw); "
           "extension: modes (decay_scale, level_db).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kLfPersistence); }

  Finding detect(const DecisionContext& ctx) const override { return decide_modes(ctx.obs()); }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    const DiagnoseOptions& options = ctx.options();
    const double schroeder = median_of(obs.each([](const RirObservation& r) { return r.schroeder_hz; }));
    std::vector<double> ratio;
    for (size_t i : ctx.fit_index()) {
      for (int b = 0; b < kNumOctaveBands && kOctaveCentersHz[b] < 2.0 * schroeder; ++b) {
        // Decay rates from T30, or T20 where a slow low band's decay in a short file has too
        // little dynamic range for T30 (then T30 alone left the fit at 1 for modes decaying 2.5x
        // more slowly than the walls make them).
        ratio.push_back(obs[i].sim_a.decay_rate_per_s[b] / obs[i].meas.decay_rate_per_s[b]);
      }
    }
    // At least 1: modes stronger or less damped than the simulation's only slow the decay; a low
    // band decaying faster than simulated is band_absorption's (decay_rate_effects.h), and a
    // decay_scale below 1 on top of its refit would count that change twice.
    const double decay_scale = std::clamp(std::isfinite(median_of(ratio)) ? median_of(ratio) : 1.0, 1.0, 4.0);
    // Level: one trial render of the fit part with the modes at 0 dB.
    const std::string trial = options.baseline_model + "+modes:decay_scale=" + spec_num(decay_scale);
    const std::vector<size_t>& fit_index = ctx.fit_index();
    std::vector<double> trial_ratio(fit_index.size()), meas_ratio(fit_index.size());
    parallel_for(fit_index.size(), options.num_threads, [&](size_t k) {
      const size_t i = fit_index[k];
      const Signal s = render_rir(trial, obs[i].room, options.sample_rate_hz, obs[i].measured.size(), options.seed);
      // The share of energy below the Schroeder frequency, as in the features.
      trial_ratio[k] = obs[i].features_of(s).lf_energy_ratio;
      meas_ratio[k] = obs[i].meas.lf_energy_ratio;
    });
    const double level_db =
        std::clamp(10.0 * std::log10(median_of(meas_ratio) / median_of(trial_ratio)), -20.0, 20.0);
    finding->parameters = {{"decay_scale", decay_scale}, {"level_db", level_db}, {"crossover_hz", schroeder}};
    return {"+modes:decay_scale=" + spec_num(decay_scale) + ",level_db=" + spec_num(std::isfinite(level_db) ? level_db : 0.0),
            {}};
  }

  void report_example(const ExampleCurves& ex, std::ostream& html) const override {
    PlotSpec p;
    p.title = "Low-frequency magnitude (red: predicted modes)";
    p.x_label = "Hz";
    p.y_label = "dB (3 Hz smoothing)";
    std::vector<double> f;
    for (size_t i = 0; i < ex.lf_meas_db.size(); ++i) f.push_back(static_cast<double>(i));
    p.x_min = 20;
    p.x_max = f.empty() ? 250 : f.back();
    p.x_markers = ex.mode_freqs_hz;
    // Each curve normalised to its own mean level in the range (calibration gains differ).
    auto norm = [&](const std::vector<double>& v) {
      std::vector<double> in_range;
      for (size_t i = 20; i < v.size(); ++i) in_range.push_back(v[i]);
      const double m = mean_of(in_range);
      std::vector<double> o;
      for (double x : v) o.push_back(x - m);
      return o;
    };
    Series base{"baseline", "#ff7f0e", f, norm(ex.lf_base_db)};
    base.dashed = true;
    p.series = {{"measured", "#1f77b4", f, norm(ex.lf_meas_db)}, base, {"extended", "#2ca02c", f, norm(ex.lf_ext_db)}};
    std::vector<double> all;
    for (const Series& s : p.series) {
      for (size_t i = 20; i < s.y.size(); ++i) all.push_back(s.y[i]);
    }
    finite_range({all}, &p.y_min, &p.y_max, 2.0);
    html << svg_plot(p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_room_modes_effect() { return std::make_unique<RoomModesEffect>(); }

}  // namespace tsrir::diagnose
