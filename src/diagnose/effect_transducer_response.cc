// transducer_response: the loudspeaker/microphone chain colours the response; the same colouration
// is then in the direct sound and in the reverberant tail.
//   Statistic  direct-sound spectral shape (band levels of the direct-sound window, measured minus
//              simulated, mean over bands removed) over the bands the short direct window resolves:
//              some band beyond min_db at p < alpha / bands, AND the tail's shape agrees
//              (correlation of the mean shapes above min_correlation), which separates a chain's
//              colouration from anything that shapes the direct sound alone.
//   Extension  sim "transducer" (src/sim/transducer.h): per-band gains = median direct-sound band
//              level difference (absolute, so the calibration gain of the measurement chain is
//              part of the filter); bands below 500 Hz take the tail's level difference aligned to
//              the direct-sound estimate.
//   Threshold  min_db; when source_directivity AND an absorption effect are detected,
//              min_db_band_refitted instead: there the fitted directivity is the direct-to-tail
//              ratio change, so the direct sound net of it IS the tail's change re the band-refitted
//              simulations, and the rule can only read the band refit's tail-level error, which on
//              sets with no transducer (a directional source and per-band absorption hidden, 30 sets
//              of bench/diagnose/diagnose_probe, seeds 1001-1030) reached 0.45-4.7 dB (mean 2.0): at
//              min_db it fired on 20 of 30; min_db_band_refitted is above 29 of them
//              (docs/results/diagnose_power.md). Only a colouration beyond it is found in that case.
//   Depends    source_directivity: a directional source raises the direct sound alone, by its
//              directivity index per band, which shapes the direct sound without being the chain's
//              colouration. When it is detected, the direct-sound differences are taken net of its
//              per-band estimate, in the decision and in the fitted gains (the chain's colouration is
//              what the direct sound and the tail share), and the decision uses the simulations
//              the directivity was decided against (band-refitted when air_absorption or
//              band_absorption is detected: its estimate is the direct sound's rise re those
//              simulations' tail).
#include <algorithm>
#include <cmath>

#include "diagnose/decay_rate_effects.h"
#include "diagnose/decision_rules.h"
#include "diagnose/diagnose.h"
#include "diagnose/extension_fit.h"
#include "diagnose/svg_plot.h"
#include "sim/transducer.h"

namespace tsrir::diagnose {
namespace {

struct TransducerThresholds {
  double min_db = 1.0;
  double min_db_band_refitted = 4.0;
  double min_correlation = 0.6;
  std::vector<Threshold> list() const {
    return {{"min_db", min_db,
             "some band of the direct sound's spectral shape departs by this much (about the just-noticeable "
             "level difference of a band) at p < alpha / bands"},
            {"min_db_band_refitted", min_db_band_refitted,
             "min_db when a directional source and an absorption mismatch are both detected: the decision then reads "
             "the band refit's tail-level error, 0.45-4.7 dB on 30 sets with no transducer; 4 dB is above 29 of them"},
            {"min_correlation", min_correlation,
             "and the tail's mean shape correlates with the direct sound's above this (the chain colours both)"}};
  }
};
constexpr TransducerThresholds kThresholds{};

class TransducerResponseEffect : public Effect {
 public:
  std::string name() const override { return "transducer_response"; }
  std::string description() const override {
    return "the measurement chain colours the response: the direct sound's spectral shape departs from the "
           "simulation's and the tail's shape agrees; extension: transducer (per-band gains, dB).";
  }
  std::vector<Threshold> thresholds() const override { return kThresholds.list(); }
  GainMetricId gain_metric() const override { return GainMetricId::own(OwnMetric::kLevelPerBand); }
  std::vector<std::string> depends_on() const override {
    return {"air_absorption", "band_absorption", "source_directivity"};
  }

  Finding detect(const DecisionContext& ctx) const override {
    const bool directional = ctx.detected("source_directivity");
    const bool refitted = directional && (ctx.detected("air_absorption") || ctx.detected("band_absorption"));
    const SetObservations& obs = refitted ? band_refitted(ctx) : ctx.obs();
    const double min_db = refitted ? kThresholds.min_db_band_refitted : kThresholds.min_db;
    const size_t n = obs.size();
    const double fs = obs.sample_rate_hz();
    Finding transducer;
    transducer.effect = name();
    std::vector<int> bands;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (direct_band_reliable(b, fs)) bands.push_back(b);
    }
    // The direct sound's share of a detected source directivity (measured side only; the seeds of
    // the null are both omni).
    BandValues directivity_db{};
    if (directional) {
      const std::vector<double>& di = ctx.finding("source_directivity").curves.at("di_db");
      for (int b : bands) directivity_db[b] = di[b];
    }
    // x: the measurement or seed B, against seed A.
    auto shapes = [&](RirFeatures RirObservation::*x, bool direct, const BandValues& net) {
      std::vector<std::vector<double>> s(kNumOctaveBands, std::vector<double>(n, NAN));
      for (size_t i = 0; i < n; ++i) {
        double m = 0.0;
        int c = 0;
        BandValues dlt{};
        const RirFeatures &xi = obs[i].*x, &yi = obs[i].sim_a;
        for (int b : bands) {
          dlt[b] = direct ? xi.direct_band_db[b] - yi.direct_band_db[b] - net[b]
                          : xi.tail_band_db[b] - yi.tail_band_db[b];
          if (std::isfinite(dlt[b])) { m += dlt[b]; ++c; }
        }
        if (c == 0) continue;
        for (int b : bands) s[b][i] = dlt[b] - m / c;
      }
      return s;
    };
    const double t_crit = t_critical(kDecision.alpha / std::max<size_t>(1, bands.size()), std::max<double>(2.0, n - 1.0));
    auto rule = [&](RirFeatures RirObservation::*x, const BandValues& net, double* max_abs, double* corr, double* p_min,
                    int* worst, BandValues* dshape, BandValues* tshape) {
      const auto ds = shapes(x, true, net), ts = shapes(x, false, net);
      std::vector<double> dm, tm;
      bool any = false;
      *max_abs = 0.0;
      *p_min = 1.0;
      *worst = -1;
      for (int b : bands) {
        const OneSampleTest t = t_test(ds[b]);
        (*dshape)[b] = t.mean;
        (*tshape)[b] = mean_of(ts[b]);
        dm.push_back(t.mean);
        tm.push_back((*tshape)[b]);
        if (std::abs(t.mean) > *max_abs) { *max_abs = std::abs(t.mean); *worst = b; }
        if (std::abs(t.mean) > min_db && std::abs(t.t) > t_crit) any = true;
        *p_min = std::min(*p_min, t.p_two_sided * bands.size());
      }
      *corr = correlation(dm, tm);
      return any && *corr > kThresholds.min_correlation;
    };
    double mx, corr, pmin, mxn, corrn, pminn;
    int worst, worstn;
    BandValues ds{}, ts{}, dsn{}, tsn{};
    const bool fires = rule(&RirObservation::meas, directivity_db, &mx, &corr, &pmin, &worst, &ds, &ts);
    const bool null_fires = rule(&RirObservation::sim_b, BandValues{}, &mxn, &corrn, &pminn, &worstn, &dsn, &tsn);
    transducer.detected = fires && !null_fires;
    transducer.statistic = mx;
    transducer.null_statistic = mxn;
    transducer.threshold = min_db;
    transducer.statistic_unit = "dB";
    transducer.confidence = confidence_of(std::min(1.0, pmin), mx, min_db, transducer.detected);
    transducer.evidence = "direct-sound spectral shape departs by up to " + num(mx) + " dB" +
                          (worst >= 0 ? " (at " + band_name(worst) + ")" : std::string()) +
                          " from the simulation (threshold " + num(min_db) + " dB at |t| > " + num(t_crit) +
                          "), and the tail's shape correlates with it at r = " + num(corr) + " (needs > " +
                          num(kThresholds.min_correlation) + "); seed-vs-seed " + num(mxn) + " dB, r = " + num(corrn) + "." +
                          (directional ? std::string(" The direct sound is taken net of the detected source directivity") +
                                             (refitted ? ", both against band-refitted simulations." : ".")
                                       : std::string());
    // The report's shape plot (bands the direct window does not resolve stay 0: not plotted).
    transducer.curves["direct_shape_db"].assign(ds.begin(), ds.end());
    transducer.curves["tail_shape_db"].assign(ts.begin(), ts.end());
    return transducer;
  }

  Extension fit(const FitContext& ctx, Finding* finding) const override {
    const SetObservations& obs = ctx.obs();
    const double fs = ctx.options().sample_rate_hz;
    sim::BandValues gain;
    gain.fill(NAN);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (!direct_band_reliable(b, fs)) continue;
      std::vector<double> d;
      for (size_t i : ctx.fit_index()) d.push_back(obs[i].meas.direct_band_db[b] - obs[i].sim_a.direct_band_db[b]);
      gain[b] = median_of(d);
    }
    if (ctx.detected("source_directivity")) {
      const auto& di = ctx.finding("source_directivity").parameters;  // one "di<band>_db" per band
      for (int b = 0; b < kNumOctaveBands && b < static_cast<int>(di.size()); ++b) {
        if (std::isfinite(gain[b])) gain[b] -= di[b].second;
      }
    }
    // Bands the short direct window cannot resolve (below 500 Hz) take the tail's level
    // difference, aligned to the direct-sound estimate over the bands both resolve (the tail
    // carries the same colouration plus the overall reverberant level).
    sim::BandValues tail_delta;
    tail_delta.fill(NAN);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      std::vector<double> d;
      for (size_t i : ctx.fit_index()) d.push_back(obs[i].meas.tail_band_db[b] - obs[i].sim_a.tail_band_db[b]);
      tail_delta[b] = median_of(d);
    }
    std::vector<double> offset;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (std::isfinite(gain[b]) && std::isfinite(tail_delta[b])) offset.push_back(tail_delta[b] - gain[b]);
    }
    const double tail_offset = offset.empty() ? 0.0 : mean_of(offset);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (!std::isfinite(gain[b]) && std::isfinite(tail_delta[b]) && kOctaveCentersHz[b] < 500.0) {
        gain[b] = tail_delta[b] - tail_offset;
      }
    }
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (std::isfinite(gain[b])) continue;
      for (int d = 1; d < kNumOctaveBands && !std::isfinite(gain[b]); ++d) {
        if (b - d >= 0 && std::isfinite(gain[b - d])) gain[b] = gain[b - d];
        else if (b + d < kNumOctaveBands && std::isfinite(gain[b + d])) gain[b] = gain[b + d];
      }
      if (!std::isfinite(gain[b])) gain[b] = 0.0;
    }
    std::string spec = "+transducer:";
    finding->parameters.clear();
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const double g = std::clamp(gain[b], -60.0, 60.0);
      spec += (b ? "," : "") + sim::transducer_gain_key(b) + "=" + spec_num(g);
      finding->parameters.push_back({sim::transducer_gain_key(b) + "_db", g});
    }
    return {spec, {}};
  }

  void report_set(const Finding& f, const Diagnosis&, std::ostream& html) const override {
    PlotSpec p = octave_band_plot("Spectral shape (mean over bands removed)", "measured - simulated, dB");
    std::vector<double> ds, ts;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const double d = f.curves.at("direct_shape_db")[b], t = f.curves.at("tail_shape_db")[b];
      ds.push_back(d == 0.0 ? NAN : d);
      ts.push_back(t == 0.0 ? NAN : t);
    }
    Series a{"direct sound", "#d62728", octave_band_axis(), ds};
    a.points = true;
    Series b{"tail", "#9467bd", octave_band_axis(), ts};
    const Series zero = octave_band_zero_line();
    finite_range({ds, ts, {2.0, -2.0}}, &p.y_min, &p.y_max, 1.0);
    p.series = {zero, a, b};
    html << svg_plot(p);
  }
};

}  // namespace

std::unique_ptr<Effect> make_transducer_response_effect() { return std::make_unique<TransducerResponseEffect>(); }

}  // namespace tsrir::diagnose
