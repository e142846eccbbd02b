// room_modes: low-frequency room modes stronger (less damped, or less smeared) than the geometric
// simulation's image sources give them.
//   Statistic  mode prominence: the spectrum of the response from 150 ms after the onset (where
//              less damped modes stand out), its maxima within the modal half-bandwidth of the
//              stated room's predicted modes minus its typical window maximum (a grid over the
//              modes' range), each relative to the local mean level over +-10 Hz, so that a smooth
//              trend such as a loudspeaker's low-frequency roll-off cancels (rir_features.h);
//              paired mean over the set, one-sided.
//   Revision   lower absorption also makes the image sources (which are the rigid-room modal sum,
//              cut at the transition time) more modal: when band_absorption is detected too,
//              room_modes is decided again against simulations with every band's absorption
//              refitted (the explain-away order: a per-band absorption error is the simpler
//              cause). If that rules the modes out, the effects depending on room_modes (air and
//              band absorption) are decided again (effect.h).
//   Extension  sim "modes" (src/sim/room_modes.h): the modal sum crossed over with the geometric
//              part below the Schroeder frequency; decay_scale = median measured / simulated T30
//              of the bands below twice the Schroeder frequency, level_db from one trial render of
//              the fit RIRs (energy share below the Schroeder frequency, measured / trial).
#include <algorithm>
#include <cmath>

#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"
#include "util/log.h"
#include "util/parallel.h"

namespace tsrir::diagnose {
namespace {

struct RoomModesThresholds {
  // Set from the statistic's null distribution, not tuned for power: over 30 independent
  // "measured" sets with nothing hidden (tests' generator, seeds 1001-1030, 24 fit RIRs each) the
  // set mean was 0.02 +- 0.06 dB (largest 0.15); 0.25 dB is ~4 s.d. above it
  // (docs/results/diagnose_power.md).
  double min_db = 0.25;
  std::vector<Threshold> list() const {
    return {{"min_db", min_db,
             "mean late-spectrum mode prominence above the simulation's (sets with nothing hidden: 0.02 +- 0.06 dB)"}};
  }
};
constexpr RoomModesThresholds kThresholds{};

Finding decide_modes(const SetObservations& obs) {
  return decide_mean(
      "room_modes", paired(obs.meas, obs.sim_a, [](const RirFeatures& f) { return f.mode_prominence_db; }),
      paired(obs.sim_b, obs.sim_a, [](const RirFeatures& f) { return f.mode_prominence_db; }), kThresholds.min_db, +1,
      "late spectrum (from 150 ms) at the predicted shoebox modes above its typical level (window maxima, each re the "
      "local mean level over +-10 Hz)",
      "dB");
}

class RoomModesEffect : public Effect {
 public:
  std::string name() const override { return "room_modes"; }
  std::string description() const override {
    return "low-frequency modes stronger than the simulation's: spectrum maxima at the stated room's predicted modes "
           "minus maxima between them, each re the local mean level (+-10 Hz); extension: modes "
           "(decay_scale, level_db).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  std::string gain_metric() const override { return "lf_spectral_distance"; }

  Finding detect(const DecisionContext& ctx) const override { return decide_modes(ctx.obs()); }

  std::vector<std::string> revised_after() const override { return {"band_absorption"}; }
  void revise(const DecisionContext& ctx, Finding* finding) const override {
    if (!ctx.detected("band_absorption") || !finding->detected) return;
    log_info("re-deciding room_modes against band-refitted simulations");
    *finding = decide_modes(ctx.band_refitted());
    finding->evidence += " (decided against simulations with the per-band absorption refit, which also "
                         "strengthens the image sources' modal structure)";
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    const DiagnoseOptions& options = ctx.options();
    const double schroeder = median_of(obs.schroeder_hz);
    std::vector<double> ratio;
    for (size_t i : ctx.fit_index()) {
      for (int b = 0; b < kNumOctaveBands && kOctaveCentersHz[b] < 2.0 * schroeder; ++b) {
        ratio.push_back(obs.meas[i].t30_s[b] / obs.sim_a[i].t30_s[b]);
      }
    }
    const double decay_scale = std::clamp(std::isfinite(median_of(ratio)) ? median_of(ratio) : 1.0, 0.5, 4.0);
    // Level: one trial render of the fit part with the modes at 0 dB.
    const std::string trial = options.baseline_model + "+modes:decay_scale=" + spec_num(decay_scale);
    const std::vector<size_t>& fit_index = ctx.fit_index();
    std::vector<double> trial_ratio(fit_index.size()), meas_ratio(fit_index.size());
    parallel_for(fit_index.size(), options.num_threads, [&](size_t k) {
      const size_t i = fit_index[k];
      const Signal s = render_rir(trial, obs.rooms[i], options.sample_rate_hz, obs.measured[i].size(), options.seed);
      // The share of energy below the Schroeder frequency, as in the features.
      trial_ratio[k] = compute_features(s, {}, obs.schroeder_hz[i], obs.t60_low_s[i]).lf_energy_ratio;
      meas_ratio[k] = obs.meas[i].lf_energy_ratio;
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
