// noise_floor: stationary measurement noise; the decay flattens at a level instead of going on.
//   Statistic  decay over the last 30 % of the file (level at 70-80 % minus 90-100 %, median of
//              the 500 Hz..4 kHz bands), paired: mean difference below -min_db, AND the measured
//              late decay flat (set median below flat_db). A double-slope decay (slow modes,
//              filter leakage) still decays and is not noise.
//   Extension  sim "noise_floor" (src/sim/noise_floor.h): per-band late power of the measurements
//              where it exceeds the simulation's by 6 dB and the band is flat, fitted by a tilted
//              white noise (level at 1 kHz re the RIR energy, tilt per octave, band edges).
#include <algorithm>
#include <cmath>

#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "dsp/octave_filter.h"
#include "sim/noise_floor.h"

namespace tsrir::diagnose {
namespace {

struct NoiseFloorThresholds {
  double min_db = 6.0;
  double flat_db = 3.0;
  std::vector<Threshold> list() const {
    return {{"min_db", min_db,
             "the measured late decay is this much smaller than the simulation's (a 1 s file of any plausible room "
             "decays > 5 dB over its last 30 %)"},
            {"flat_db", flat_db,
             "and the measured late decay is flatter than this (set median): noise stops the decay, a double slope "
             "does not"}};
  }
};
constexpr NoiseFloorThresholds kThresholds{};

// Noise power fraction an octave filter passes of tilted white noise (relative to the noise's
// per-sample power at the 1 kHz density): integral of |H|^2 g(f) df / (fs / 2).
double band_noise_fraction(int band, double tilt, double fs, double lo_hz, double hi_hz) {
  const SosFilter filter = ansi_octave_filter(kOctaveCentersHz[band], fs, 3);
  constexpr int kGrid = 4096;
  double s = 0.0;
  for (int k = 1; k < kGrid; ++k) {
    const double f = 0.5 * fs * k / kGrid;
    s += std::norm(sos_response(filter, f, fs)) * sim::noise_tilt_power_gain(f, tilt, lo_hz, hi_hz);
  }
  return s / kGrid;
}

class NoiseFloorEffect : public Effect {
 public:
  std::string name() const override { return "noise_floor"; }
  std::string description() const override {
    return "stationary measurement noise: the measured decay over the last 30 % of the file is flat where the "
           "simulation's still decays; extension: noise_floor (level, tilt, band edges).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kTailLevel); }
  std::vector<ResidualView> residual_views() const override { return {ResidualView::kDecayShape}; }

  Finding detect(const DecisionContext& ctx) const override {
    const SetObservations& obs = ctx.obs();
    Finding noise = decide_mean(
        name(), measured_minus_sim(obs, [](const RirFeatures& f) { return f.late_decay_db; }),
        seed_b_minus_a(obs, [](const RirFeatures& f) { return f.late_decay_db; }), kThresholds.min_db, -1,
        "decay over the last 30 % of the file (level at 70-80 % minus 90-100 %, 500 Hz-4 kHz median)", "dB");
    const double flat = median_of(obs.each([](const RirObservation& r) { return r.meas.late_decay_db; }));
    if (noise.detected && !(flat < kThresholds.flat_db)) noise.detected = false;
    noise.evidence += " Measured late decay (median over the set) " + num(flat) + " dB; flat below " +
                      num(kThresholds.flat_db) + " dB is required.";
    if (!noise.detected) noise.confidence = std::min(noise.confidence, 0.49);
    return noise;
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    const double fs = ctx.options().sample_rate_hz;
    std::vector<int> bands;
    sim::BandValues observed{};
    for (int b = 0; b < kNumOctaveBands; ++b) {
      // Only bands whose end is noise: flat in most RIRs; a band still decaying there (long
      // low-frequency reverberation) says nothing about noise. Noise: 4x (6 dB) the simulation's
      // late power.
      std::vector<double> l, flatness;
      for (size_t i : ctx.fit_index()) {
        const double pm = obs[i].meas.late_power[b] / obs[i].meas.energy;
        const double ps = obs[i].sim_a.late_power[b] / obs[i].sim_a.energy;
        flatness.push_back(obs[i].meas.late_decay_band_db[b]);
        if (std::isfinite(pm) && pm > 4.0 * ps) l.push_back(10.0 * std::log10(pm - ps));
      }
      if (l.size() >= std::max<size_t>(1, ctx.fit_index().size() / 2) && median_of(flatness) < kThresholds.flat_db) {
        bands.push_back(b);
        observed[b] = median_of(l);
      }
    }
    // The slope holds between the outer edges of the bands it was fitted on.
    const double lo_hz = bands.empty() ? 20.0 : octave_lower_edge_hz(kOctaveCentersHz[bands.front()]);
    const double hi_hz = bands.empty() ? 0.5 * fs : std::min(0.5 * fs, octave_upper_edge_hz(kOctaveCentersHz[bands.back()]));
    double best_tilt = 0.0, best_level = -100.0, best_err = INFINITY;
    for (double tilt = -6.0; tilt <= 3.0001; tilt += 0.25) {
      std::vector<double> offs;
      for (int b : bands) offs.push_back(observed[b] - 10.0 * std::log10(band_noise_fraction(b, tilt, fs, lo_hz, hi_hz)));
      if (offs.empty()) break;
      const double level = mean_of(offs);
      double err = 0.0;
      for (double o : offs) err += (o - level) * (o - level);
      if (err < best_err) { best_err = err; best_level = level; best_tilt = tilt; }
    }
    best_level = std::clamp(best_level, -300.0, 0.0);
    finding->parameters = {{"level_db", best_level}, {"tilt_db_per_octave", best_tilt}, {"min_hz", lo_hz}, {"max_hz", hi_hz}};
    return {"+noise_floor:level_db=" + spec_num(best_level) + ",tilt_db_per_octave=" + spec_num(best_tilt) +
                ",min_hz=" + spec_num(lo_hz) + ",max_hz=" + spec_num(hi_hz),
            {}};
  }
};

}  // namespace

std::unique_ptr<Effect> make_noise_floor_effect() { return std::make_unique<NoiseFloorEffect>(); }

}  // namespace tsrir::diagnose
