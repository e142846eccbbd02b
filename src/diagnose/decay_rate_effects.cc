#include "diagnose/decay_rate_effects.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "diagnose/decision_rules.h"
#include "diagnose/extension_fit.h"
#include "sim/air_absorption.h"
#include "sim/room_refits.h"
#include "util/log.h"
#include "util/parallel.h"

namespace tsrir::diagnose {

std::vector<Threshold> AirAbsorptionThresholds::list() const {
  return {
      {"min_top_rate_ratio", min_top_rate_ratio,
       "the fitted ISO 9613-1 curve must predict this much faster decay in the top tested band (5 %: below that, "
       "air is within the decay rates' per-room uncertainty)"},
      {"max_chi2_fraction", max_chi2_fraction,
       "the curve may leave at most this share of the no-change chi-square (air must explain the whole mismatch)"},
      {"min_chi2_improvement", min_chi2_improvement,
       "and improve the chi-square by more than this over no change AND over one uniform rate factor for all bands "
       "(a room volume or area error; dry air's nearly flat curve would otherwise take it)"},
  };
}

std::vector<Threshold> BandAbsorptionThresholds::list() const {
  return {{"min_rate_ratio", min_rate_ratio,
           "some room's band decay rate departs by this factor (8 %: about the just-noticeable difference of "
           "reverberation time) at p < alpha / (rooms x bands), beyond the uniform change a room-size error allows"},
          {"max_size_error", max_size_error,
           "stated room dimensions are trusted to this fraction (5 %): a uniform change of every band's decay "
           "rate up to 1 / (1 - 0.05) is taken as geometry, not absorption"}};
}

double air_log_ratio(int band, const AirFit& fit, double base_rate, double temperature_c, double c) {
  if (fit.scale <= 0.0) return 0.0;
  const double inc = sim::air_band_decay_increase_per_s(kOctaveCentersHz[band], temperature_c, fit.humidity_percent, c,
                                                        base_rate);
  return std::log((base_rate + fit.scale * inc) / base_rate);
}

AirFit fit_air(const std::vector<RateObservation>& obs, double temperature_c, double c) {
  AirFit best;
  for (const RateObservation& o : obs) best.chi2_zero += std::pow(o.mean_log_ratio / o.standard_error, 2);
  best.chi2_fit = best.chi2_zero;
  const double humidities[] = {3, 5, 7.5, 10, 12.5, 15, 20, 25, 30, 40, 50, 60, 70, 85, 100};
  for (double h : humidities) {
    std::vector<double> inc;
    for (const RateObservation& o : obs) {
      inc.push_back(sim::air_band_decay_increase_per_s(kOctaveCentersHz[o.band], temperature_c, h, c, o.base_rate_per_s));
    }
    for (double scale = 0.05; scale <= 4.0001; scale += 0.05) {
      double chi2 = 0.0;
      for (size_t k = 0; k < obs.size(); ++k) {
        const RateObservation& o = obs[k];
        chi2 += std::pow((o.mean_log_ratio - std::log1p(scale * inc[k] / o.base_rate_per_s)) / o.standard_error, 2);
      }
      // Ties (the humidity/scale trade-off) go to the scale nearest 1.
      if (chi2 < best.chi2_fit - 1e-9 ||
          (std::abs(chi2 - best.chi2_fit) <= 1e-9 && std::abs(std::log(scale)) < std::abs(std::log(best.scale)))) {
        best.chi2_fit = chi2;
        best.humidity_percent = h;
        best.scale = scale;
      }
    }
  }
  return best;
}

namespace {

// What the analysis of one side (measured vs seed A, or seed B vs seed A) reads: the rooms, their
// simulated rates, the bands decided on.
struct DecaySetup {
  std::map<std::string, std::vector<size_t>> groups;  // room_group -> RIRs
  std::map<std::string, BandValues> group_base;       // per room: the simulation's median rate per band
  BandValues base{};                                  // the same over the set
  std::vector<int> tested;
  std::vector<int> low_tested;  // bands below twice the Schroeder frequency while room_modes is detected
  double t_crit = 0.0, temp = 20.0, c = 343.0;
};

// The t-test of band b's log rate ratios over one room's RIRs idx.
OneSampleTest room_band_test(const std::vector<std::vector<double>>& x, const std::vector<size_t>& idx, int b) {
  std::vector<double> v;
  for (size_t i : idx) v.push_back(x[b][i]);
  return t_test(v);
}

// Per room and tested band, the mean log rate ratio (the air fit's observations).
std::vector<RateObservation> room_band_observations(const std::vector<std::vector<double>>& x, const DecaySetup& s) {
  std::vector<RateObservation> observations;
  for (const auto& [g, idx] : s.groups) {
    if (idx.size() < 3) continue;
    for (int b : s.tested) {
      const OneSampleTest t = room_band_test(x, idx, b);
      if (t.n < 3) continue;
      observations.push_back({b, t.mean, std::max(t.standard_error, 1e-4), s.group_base.at(g)[b]});
    }
  }
  return observations;
}

// The simpler rival of air: one decay-rate factor for every band (a room volume or area that
// differs from the stated one, or absorption off by the same factor everywhere). Air must explain
// the bands better than that: dry air's ISO curve is nearly flat across the bands and would
// otherwise take a uniform change for air. Its chi-square.
double uniform_factor_chi2(const std::vector<RateObservation>& observations) {
  double sw = 0.0, swx = 0.0;
  for (const RateObservation& o : observations) {
    const double w = 1.0 / (o.standard_error * o.standard_error);
    sw += w;
    swx += w * o.mean_log_ratio;
  }
  double chi2 = 0.0;
  for (const RateObservation& o : observations) {
    chi2 += std::pow((o.mean_log_ratio - (sw > 0.0 ? swx / sw : 0.0)) / o.standard_error, 2);
  }
  return chi2;
}

// A room whose stated dimensions are off by up to max_size_error decays faster or slower in every
// band by the same factor (Eyring: the rate goes as S / V, 1 / size): that much of a uniform change
// is geometry, not absorption. The room's weighted mean change over the tested bands, clamped to
// that range.
double geometry_share(const std::vector<OneSampleTest>& tests) {
  const double max_uniform = -std::log1p(-kBandThresholds.max_size_error);
  double w_sum = 0.0, wx = 0.0;
  for (const OneSampleTest& t : tests) {
    if (t.n < 3) continue;
    const double w = 1.0 / std::pow(std::max(t.standard_error, 1e-4), 2);
    w_sum += w;
    wx += w * t.mean;
  }
  return w_sum > 0.0 ? std::clamp(wx / w_sum, -max_uniform, max_uniform) : 0.0;
}

// Which bands of which rooms depart, raw and after the air curve, each less the room's geometry
// share; the largest raw departure goes into *side.
struct BandTests {
  bool residual_significant = false, raw_significant = false, raw_significant_air = false;
};
BandTests test_bands(const std::vector<std::vector<double>>& x, const DecaySetup& s, DecayRateSide* side) {
  const double min_ratio = std::log(kBandThresholds.min_rate_ratio);
  BandTests out;
  side->worst_band = -1;
  side->worst_ratio = 0.0;
  const std::vector<int>& tested = s.tested;
  for (const auto& [g, idx] : s.groups) {
    if (idx.size() < 3) continue;
    std::vector<std::vector<double>> r(tested.size()), raw(tested.size());
    std::vector<OneSampleTest> tr(tested.size()), t0(tested.size());
    for (size_t k = 0; k < tested.size(); ++k) {
      const int b = tested[k];
      const double curve = air_log_ratio(b, side->fit, s.group_base.at(g)[b], s.temp, s.c);
      for (size_t i : idx) { r[k].push_back(x[b][i] - curve); raw[k].push_back(x[b][i]); }
      tr[k] = t_test(r[k]);
      t0[k] = t_test(raw[k]);
    }
    const double share_r = geometry_share(tr), share_0 = geometry_share(t0);
    for (size_t k = 0; k < tested.size(); ++k) {
      const int b = tested[k];
      // Air's own test reads the raw change (air is not geometry: it grows with frequency).
      if (std::abs(t0[k].mean) > std::log(kAirThresholds.min_top_rate_ratio) && std::abs(t0[k].t) > s.t_crit) {
        out.raw_significant_air = true;
      }
      for (double& v : r[k]) v -= share_r;
      for (double& v : raw[k]) v -= share_0;
      const OneSampleTest br = t_test(r[k]), b0 = t_test(raw[k]);
      if (std::abs(br.mean) > min_ratio && std::abs(br.t) > s.t_crit) out.residual_significant = true;
      if (std::abs(b0.mean) > min_ratio && std::abs(b0.t) > s.t_crit) out.raw_significant = true;
      if (std::abs(b0.mean) > std::abs(side->worst_ratio)) {
        side->worst_ratio = b0.mean;
        side->worst_band = b;
        side->worst_room = g;
      }
    }
  }
  return out;
}

// The low bands while room_modes is detected: a modal field that is stronger or less damped than
// the simulation's only slows their decay, and how much more slowly its modes decay is fitted by
// room_modes' extension (decay_scale), which a lower low-band absorption would change alike (the
// modes' damping is the walls' absorption: docs/results/diagnose_power.md). A decay FASTER than
// simulated is beyond what the modes explain: band_absorption, one-sided, per room, at the same
// effect size and t as the other bands (no geometry share: the room's other bands carry it).
void test_low_bands_faster(const std::vector<std::vector<double>>& x, const DecaySetup& s, DecayRateSide* side) {
  const double min_ratio = std::log(kBandThresholds.min_rate_ratio);
  for (const auto& [g, idx] : s.groups) {
    if (idx.size() < 3) continue;
    for (int b : s.low_tested) {
      const OneSampleTest t = room_band_test(x, idx, b);
      if (!(t.mean > min_ratio && t.t > s.t_crit)) continue;
      side->band_fires = true;
      side->low_faster_bands.push_back(b);
      if (t.mean > std::abs(side->worst_ratio)) {
        side->worst_ratio = t.mean;
        side->worst_band = b;
        side->worst_room = g;
      }
    }
  }
}

// The decisions of one side: the air fit against no change and one uniform factor, then the
// per-band tests.
void analyse_side(const std::vector<std::vector<double>>& x, const DecaySetup& s, DecayRateSide* side) {
  const std::vector<RateObservation> observations = room_band_observations(x, s);
  side->fit = fit_air(observations, s.temp, s.c);
  side->uniform_chi2 = uniform_factor_chi2(observations);
  side->air_curve.fill(NAN);
  for (int b : s.tested) side->air_curve[b] = air_log_ratio(b, side->fit, s.base[b], s.temp, s.c);
  const BandTests bands = test_bands(x, s, side);
  const double top = s.tested.empty() ? 0.0 : side->air_curve[s.tested.back()];
  const double min_gain = kAirThresholds.min_chi2_improvement;
  const AirFit& fit = side->fit;
  side->air_fires = bands.raw_significant_air && fit.scale > 0.0 && fit.chi2_fit < kAirThresholds.max_chi2_fraction * fit.chi2_zero &&
                    fit.chi2_zero - fit.chi2_fit > min_gain && side->uniform_chi2 - fit.chi2_fit > min_gain &&
                    !bands.residual_significant && top > std::log(kAirThresholds.min_top_rate_ratio);
  // With air explaining everything, the per-band refit is not needed; otherwise any band that
  // departs (raw, i.e. the refit also absorbs air) is band_absorption.
  side->band_fires = side->air_fires ? bands.residual_significant : bands.raw_significant;
  test_low_bands_faster(x, s, side);
}

}  // namespace

DecayRateAnalysis analyse_decay_rates(const SetObservations& obs, bool room_modes_detected) {
  const size_t n = obs.size();
  DecayRateAnalysis a;
  DecaySetup s;
  a.q.assign(kNumOctaveBands, {});
  std::vector<std::vector<double>> qn(kNumOctaveBands);
  std::vector<int> bands;
  a.schroeder_hz = median_of(obs.each([](const RirObservation& r) { return r.schroeder_hz; }));
  for (int b = 0; b < kNumOctaveBands; ++b) {
    size_t ok = 0;
    for (size_t i = 0; i < n; ++i) {
      const double rm = obs[i].meas.decay_rate_per_s[b], ra = obs[i].sim_a.decay_rate_per_s[b],
                   rb = obs[i].sim_b.decay_rate_per_s[b];
      a.q[b].push_back(std::log(rm / ra));
      qn[b].push_back(std::log(rb / ra));
      if (std::isfinite(rm) && std::isfinite(ra) && std::isfinite(rb)) ++ok;
    }
    s.base[b] = median_of(obs.each([b](const RirObservation& r) { return r.sim_a.decay_rate_per_s[b]; }));
    if (n > 0 && ok >= 0.8 * n && ok >= 3) bands.push_back(b);
  }
  a.low_bands_left_to_modes = room_modes_detected;
  for (int b : bands) {
    const bool low = a.low_bands_left_to_modes && kOctaveCentersHz[b] < 2.0 * a.schroeder_hz;
    (low ? s.low_tested : a.tested).push_back(b);
  }
  // Rooms (absorption is a property of each room, air of the whole campaign).
  for (size_t i = 0; i < n; ++i) s.groups[room_group(obs[i].room)].push_back(i);
  a.num_rooms = s.groups.size();
  for (const auto& [g, idx] : s.groups) {
    for (int b = 0; b < kNumOctaveBands; ++b) {
      std::vector<double> r;
      for (size_t i : idx) r.push_back(obs[i].sim_a.decay_rate_per_s[b]);
      s.group_base[g][b] = median_of(r);
    }
  }
  a.t_crit = t_critical(kDecision.alpha / std::max<size_t>(1, (a.tested.size() + s.low_tested.size()) * s.groups.size()),
                        std::max<double>(2.0, n / std::max<double>(1.0, s.groups.size()) - 1.0));
  s.tested = a.tested;
  s.t_crit = a.t_crit;
  s.temp = obs.empty() ? 20.0 : obs[0].room.temperature_c;
  s.c = obs.empty() ? 343.0 : obs[0].room.speed_of_sound_m_s;
  analyse_side(a.q, s, &a.measured);
  analyse_side(qn, s, &a.null);
  return a;
}

sim::BandValues band_absorption_scales(const SetObservations& obs, const std::vector<size_t>& idx, const AirFit& air_fit,
                                       double keep_below_hz) {
  const double temp = obs[0].room.temperature_c, c = obs[0].room.speed_of_sound_m_s;
  sim::BandValues scale;
  scale.fill(NAN);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (kOctaveCentersHz[b] < keep_below_hz) { scale[b] = 1.0; continue; }
    std::vector<double> q, r;
    for (size_t i : idx) {
      q.push_back(std::log(obs[i].meas.decay_rate_per_s[b] / obs[i].sim_a.decay_rate_per_s[b]));
      r.push_back(obs[i].sim_a.decay_rate_per_s[b]);
    }
    if (finite_values(q).size() >= std::max<size_t>(1, idx.size() / 2)) {
      const double air_share = air_fit.scale > 0.0 ? air_log_ratio(b, air_fit, median_of(r), temp, c) : 0.0;
      scale[b] = std::clamp(std::exp(median_of(q) - air_share), 0.1, 10.0);
    }
  }
  // Bands without a measurement (e.g. above Nyquist) take their nearest measured neighbour.
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (std::isfinite(scale[b])) continue;
    for (int d = 1; d < kNumOctaveBands && !std::isfinite(scale[b]); ++d) {
      if (b - d >= 0 && std::isfinite(scale[b - d])) scale[b] = scale[b - d];
      else if (b + d < kNumOctaveBands && std::isfinite(scale[b + d])) scale[b] = scale[b + d];
    }
    if (!std::isfinite(scale[b])) scale[b] = 1.0;
  }
  return scale;
}

std::string band_absorption_spec(const sim::BandValues& scale) {
  std::string spec = "band_absorption:";
  for (int b = 0; b < kNumOctaveBands; ++b) spec += (b ? "," : "") + sim::band_absorption_key(b) + "=" + spec_num(scale[b]);
  return spec;
}

sim::BandValues refine_band_scales(const SetObservations& obs, const std::vector<size_t>& idx, sim::BandValues scale,
                                   const std::string& model_prefix, const DiagnoseOptions& options, int iterations,
                                   double keep_below_hz) {
  std::array<bool, kNumOctaveBands> measured{};
  for (int it = 0; it < iterations; ++it) {
    const std::string spec = model_prefix + "+" + band_absorption_spec(scale);
    std::vector<sim::BandValues> rates(idx.size()), early(idx.size());
    parallel_for(idx.size(), options.num_threads, [&](size_t k) {
      const size_t i = idx[k];
      const Signal s = render_rir(spec, obs[i].room, options.sample_rate_hz, obs[i].measured.size(), options.seed);
      const RirFeatures f = obs[i].features_of(s);
      rates[k] = f.decay_rate_per_s;
      early[k] = f.early_decay_rate_per_s;
    });
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (kOctaveCentersHz[b] < keep_below_hz) continue;
      // Late (T30) and early (EDT) decay residuals, averaged: the early one keeps moving a band
      // whose T30 is dominated by a neighbour's leakage.
      std::vector<double> q, qe;
      for (size_t k = 0; k < idx.size(); ++k) {
        q.push_back(std::log(obs[idx[k]].meas.decay_rate_per_s[b] / rates[k][b]));
        qe.push_back(std::log(obs[idx[k]].meas.early_decay_rate_per_s[b] / early[k][b]));
      }
      if (finite_values(q).size() >= std::max<size_t>(1, idx.size() / 2)) {
        const double late = median_of(q), first = median_of(qe);
        const double step = std::isfinite(first) ? 0.5 * (late + first) : late;
        scale[b] = std::clamp(scale[b] * std::exp(step), 0.1, 10.0);
        measured[b] = true;
      }
    }
  }
  // Bands without a measurement (above Nyquist) follow their nearest refined neighbour.
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (measured[b] || kOctaveCentersHz[b] < keep_below_hz) continue;
    for (int d = 1; d < kNumOctaveBands; ++d) {
      if (b - d >= 0 && measured[b - d]) { scale[b] = scale[b - d]; break; }
      if (b + d < kNumOctaveBands && measured[b + d]) { scale[b] = scale[b + d]; break; }
    }
  }
  return scale;
}

std::map<std::string, std::string> band_refit_models(const SetObservations& obs, const DiagnoseOptions& options) {
  std::map<std::string, std::vector<size_t>> by_room;
  for (size_t i = 0; i < obs.size(); ++i) by_room[room_group(obs[i].room)].push_back(i);
  std::map<std::string, std::string> spec;
  for (const auto& [room, idx] : by_room) {
    const sim::BandValues scale = refine_band_scales(obs, idx, band_absorption_scales(obs, idx, AirFit{}, 0.0),
                                                     options.baseline_model, options, 3, 0.0);
    spec[room] = options.baseline_model + "+" + band_absorption_spec(scale);
    log_info("band refit of " + room + ": " + spec[room]);
  }
  return spec;
}

std::string band_refit_pooled_model(const SetObservations& obs, const DiagnoseOptions& options) {
  std::vector<size_t> idx(obs.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const sim::BandValues scale = refine_band_scales(obs, idx, band_absorption_scales(obs, idx, AirFit{}, 0.0),
                                                   options.baseline_model, options, 3, 0.0);
  const std::string spec = options.baseline_model + "+" + band_absorption_spec(scale);
  log_info("band refit pooled over the fit half's " + std::to_string(obs.size()) + " RIRs: " + spec);
  return spec;
}

const SetObservations& band_refitted(const DecisionContext& ctx) {
  return ctx.reference(kBandRefittedReference, render_band_refitted);
}

SetObservations render_band_refitted(const SetObservations& obs, const DiagnoseOptions& options) {
  const std::map<std::string, std::string> spec = band_refit_models(obs, options);
  SetObservations refit = obs;
  refit.model_by_room = spec;
  parallel_for(obs.size(), options.num_threads, [&](size_t i) {
    const std::string& s = spec.at(room_group(obs[i].room));
    const Signal a = render_rir(s, obs[i].room, options.sample_rate_hz, obs[i].measured.size(), options.seed);
    const Signal b = render_rir(s, obs[i].room, options.sample_rate_hz, obs[i].measured.size(), options.seed + 1);
    refit[i].sim_a = obs[i].features_of(a);
    refit[i].sim_b = obs[i].features_of(b);
  });
  return refit;
}

}  // namespace tsrir::diagnose
