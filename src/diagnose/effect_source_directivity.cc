// source_directivity: the source is a directional loudspeaker aimed at the microphone, not the omni
// source the simulation assumes. For the same radiated power it puts more energy into the direct
// sound (the directivity factor Q on its axis) while the diffuse field keeps its level, so the
// direct-to-reverberant ratio is higher than simulated by the directivity index DI = 10 log10 Q at
// every distance, and more so at high frequencies (a small box is omnidirectional where the
// wavelength exceeds it). Nothing else changes: the decay, the onsets and the tail's spectrum are
// right.
//   Statistic  per RIR and per band the direct-sound window's level minus the tail window's
//              (20-300 ms after the onset), measured minus simulated, averaged over the bands the
//              short direct window resolves and whose decay is measured (whole octaves below
//              Nyquist) (so a transducer's colouration, common to both windows, cancels); paired one-sided mean over the set above min_db. A position error
//              moves single RIRs' ratios both ways; only a consistent shift is directivity.
//   Depends    air_absorption, band_absorption: a decay mismatch changes the tail window's level
//              too (a faster decay leaves less energy in it). When either is detected, the ratio is
//              decided against simulations with every band's absorption refitted to the measured
//              decay (decay_rate_effects.h: band_refitted), so that only what the decay does not
//              explain is left (the explain-away order: the decay is the simpler cause).
//   Extension  sim "directivity" (src/sim/source_directivity.h): DI per band = the median ratio
//              change over the fit RIRs in the bands the direct window resolves; 0 dB below them
//              (omnidirectional at low frequencies), the nearest resolved band's above them.
//              transducer_response depends on this effect: its direct-sound gains are taken net
//              of the fitted directivity.
#include <algorithm>
#include <cmath>

#include "diagnose/decay_rate_effects.h"
#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"
#include "sim/source_directivity.h"

namespace tsrir::diagnose {
namespace {

struct SourceDirectivityThresholds {
  double min_db = 1.0;
  std::vector<Threshold> list() const {
    return {{"min_db", min_db,
             "mean rise of the direct-to-tail level ratio over the direct-resolved bands (a directivity index of 1 dB, "
             "Q = 1.26, is within what omnidirectional measurement sources show at mid frequencies; beyond it the "
             "source is directional)"}};
  }
};
constexpr SourceDirectivityThresholds kThresholds{};

// Per band: direct-window level minus tail-window level of x (the measurement, or seed B) minus the
// same of seed A, per RIR.
std::vector<std::vector<double>> ratio_change(const SetObservations& obs, RirFeatures RirObservation::*x,
                                              const std::vector<int>& bands) {
  std::vector<std::vector<double>> out(kNumOctaveBands);
  for (int b : bands) {
    for (const RirObservation& r : obs) {
      const RirFeatures& f = r.*x;
      out[b].push_back((f.direct_band_db[b] - f.tail_band_db[b]) - (r.sim_a.direct_band_db[b] - r.sim_a.tail_band_db[b]));
    }
  }
  return out;
}

// Per RIR: the mean over the bands of its finite changes.
std::vector<double> band_mean(const std::vector<std::vector<double>>& change, const std::vector<int>& bands, size_t n) {
  std::vector<double> out(n, NAN);
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0;
    int c = 0;
    for (int b : bands) {
      if (std::isfinite(change[b][i])) { s += change[b][i]; ++c; }
    }
    if (c > 0) out[i] = s / c;
  }
  return out;
}

class SourceDirectivityEffect : public Effect {
 public:
  std::string name() const override { return "source_directivity"; }
  std::string description() const override {
    return "a directional source aimed at the microphone: the direct sound's level re the tail (20-300 ms) is higher "
           "than the omni simulation's in the bands the direct window resolves, with the decay right (decided against "
           "band-refitted simulations when a decay mismatch is detected); extension: directivity (directivity index "
           "per band, dB).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::column("DRR"); }
  std::vector<ResidualView> residual_views() const override { return {ResidualView::kEarlyPattern}; }
  std::vector<std::string> depends_on() const override { return {"air_absorption", "band_absorption"}; }

  Finding detect(const DecisionContext& ctx) const override {
    const bool decay_refitted = ctx.detected("air_absorption") || ctx.detected("band_absorption");
    const SetObservations& obs = decay_refitted ? band_refitted(ctx) : ctx.obs();
    const size_t n = obs.size();
    const double fs = obs.sample_rate_hz();
    // Bands the direct window resolves and whose decay is measured (a whole octave below Nyquist):
    // a half band at Nyquist has no decay of its own to refit the tail's reference with.
    std::vector<int> bands;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (direct_band_reliable(b, fs) && octave_upper_edge_hz(kOctaveCentersHz[b]) <= 0.5 * fs) bands.push_back(b);
    }
    const auto d = ratio_change(obs, &RirObservation::meas, bands), e = ratio_change(obs, &RirObservation::sim_b, bands);
    Finding f = decide_mean(name(), band_mean(d, bands, n), band_mean(e, bands, n), kThresholds.min_db, +1,
                            "direct-to-tail level ratio (direct window vs 20-300 ms), mean over the bands the direct "
                            "window resolves",
                            "dB");
    if (decay_refitted) {
      f.evidence += " Decided against simulations with every band's absorption refitted to the measured decay (a decay "
                    "mismatch moves the tail level too).";
    }
    // Per band: median (the fit) and mean +- s.e. (the report) of the change.
    std::vector<double>& median = f.curves["median_change_db"];
    std::vector<double>& mean = f.curves["mean_change_db"];
    std::vector<double>& se = f.curves["se_change_db"];
    median.assign(kNumOctaveBands, NAN);
    mean.assign(kNumOctaveBands, NAN);
    se.assign(kNumOctaveBands, NAN);
    for (int b : bands) {
      const OneSampleTest t = t_test(d[b]);
      median[b] = median_of(d[b]);
      if (t.n) { mean[b] = t.mean; se[b] = t.standard_error; }
    }
    // The directivity index per band (what the extension applies and what transducer_response
    // takes out of the direct sound): the median where measured; 0 dB below (omnidirectional at
    // low frequencies), the highest measured band's value above.
    std::vector<double>& di = f.curves["di_db"];
    di.assign(kNumOctaveBands, 0.0);
    int last = -1;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (std::isfinite(median[b])) {
        di[b] = std::clamp(median[b], -20.0, 20.0);
        last = b;
      } else if (last >= 0) {
        di[b] = di[last];
      }
    }
    return f;
  }

  Extension fit(const FitContext&, Finding* finding) const override {
    // The decision was made on the fit RIRs against the right reference (band-refitted when a decay
    // mismatch was detected): its per-band estimate is the fit.
    const std::vector<double>& di = finding->curves.at("di_db");
    std::string spec = "+directivity:";
    finding->parameters.clear();
    for (int b = 0; b < kNumOctaveBands; ++b) {
      spec += (b ? "," : "") + sim::directivity_key(b) + "=" + spec_num(di[b]);
      finding->parameters.push_back({sim::directivity_key(b) + "_db", di[b]});
    }
    return {spec, {}};
  }

  void report_set(const Finding& f, const Diagnosis&, std::ostream& html) const override {
    PlotSpec p = octave_band_plot("Direct-to-tail level ratio, measured - simulated", "dB (+ = more direct sound)");
    Series s{"mean +- 2 s.e.", "#1f77b4", octave_band_axis(), f.curves.at("mean_change_db")};
    s.points = true;
    for (double v : f.curves.at("se_change_db")) s.y_error.push_back(2.0 * v);
    std::vector<double> fitted;
    for (const auto& [k, v] : f.parameters) fitted.push_back(v);
    const Series zero = octave_band_zero_line();
    p.series = {zero, s};
    if (fitted.size() == static_cast<size_t>(kNumOctaveBands)) {
      Series di{"fitted directivity index", "#2ca02c", octave_band_axis(), fitted};
      di.dashed = true;
      p.series.push_back(di);
    }
    finite_range({s.y, fitted, {2.0, -2.0}}, &p.y_min, &p.y_max, 1.0);
    html << svg_plot(p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_source_directivity_effect() { return std::make_unique<SourceDirectivityEffect>(); }

}  // namespace tsrir::diagnose
