#include "diagnose/effects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "diagnose/set_statistics.h"
#include "sim/air_absorption.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

std::string num(double v, int digits = 3) { return std::isfinite(v) ? format_double(v, digits) : "n/a"; }

std::string band_name(int b) { return octave_band_label(kOctaveCentersHz[b]) + " Hz"; }

// Critical |t| for a two-sided p at dof degrees of freedom (bisection on the exact tail).
double t_critical(double p, double dof) {
  double lo = 0.0, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_two_sided_p(mid, dof) > p ? lo : hi) = mid;
  }
  return hi;
}

double confidence_of(double p, double effect, double threshold, bool detected) {
  double c = std::clamp(1.0 - p, 0.0, 1.0) * std::clamp(std::abs(effect) / threshold, 0.0, 1.0);
  if (!std::isfinite(c)) c = 0.0;
  return detected ? std::max(c, 0.5) : std::min(c, 0.49);
}

template <typename F>
std::vector<double> paired(const std::vector<RirFeatures>& a, const std::vector<RirFeatures>& b, F f) {
  std::vector<double> d(a.size());
  for (size_t i = 0; i < a.size(); ++i) d[i] = f(a[i]) - f(b[i]);
  return d;
}

// A paired-mean effect: decided on d (measured - sim A), calibrated on e (sim B - sim A).
struct MeanDecision {
  bool fires = false;
  OneSampleTest test;
};
MeanDecision mean_rule(const std::vector<double>& d, double min_effect, int sign /* +1, -1, 0 = both */) {
  MeanDecision r;
  r.test = t_test(d);
  const bool direction_ok = sign == 0 || (sign > 0 ? r.test.mean > 0 : r.test.mean < 0);
  r.fires = r.test.n >= 3 && direction_ok && std::abs(r.test.mean) > min_effect && r.test.p_two_sided < kThresholds.alpha;
  return r;
}

Finding decide_mean(const std::string& effect, const std::vector<double>& d, const std::vector<double>& e,
                    double min_effect, int sign, const std::string& what, const std::string& unit) {
  Finding f;
  f.effect = effect;
  const MeanDecision m = mean_rule(d, min_effect, sign);
  const MeanDecision null = mean_rule(e, min_effect, sign);
  f.statistic = m.test.mean;
  f.null_statistic = null.test.mean;
  f.threshold = min_effect;
  f.statistic_unit = unit;
  f.detected = m.fires && !null.fires;
  f.confidence = confidence_of(m.test.p_two_sided, m.test.mean, min_effect, f.detected);
  f.evidence = what + ": measured - simulated = " + num(m.test.mean) + " +- " + num(m.test.standard_error) + " " + unit +
               " over " + std::to_string(m.test.n) + " RIRs (t = " + num(m.test.t) + ", p = " + num(m.test.p_two_sided, 2) +
               "; threshold " + num(min_effect) + " " + unit + " at p < " + num(kThresholds.alpha) + "); seed-vs-seed " +
               num(null.test.mean) + " " + unit + (null.fires ? " (null also fires: statistic not trusted)" : "") + ".";
  return f;
}

}  // namespace

std::string room_group(const sim::RoomSpec& room) {
  if (!room.room_id.empty()) return room.room_id;
  std::string acoustic;
  for (const auto& surface : room.absorption) {
    for (double a : surface) acoustic += format_double(a, 6) + ",";
  }
  for (double s : room.scattering) acoustic += format_double(s, 6) + ",";
  char hash[16];
  std::snprintf(hash, sizeof hash, "%06llx", static_cast<unsigned long long>(stable_hash(acoustic) & 0xffffff));
  return "room" + format_double(room.size_m[0], 4) + "x" + format_double(room.size_m[1], 4) + "x" +
         format_double(room.size_m[2], 4) + "-" + hash;
}

const std::vector<std::string>& effect_catalog() {
  static const std::vector<std::string> kCatalog = {"room_modes",  "air_absorption",     "band_absorption",
                                                    "transducer_response", "noise_floor", "diffuse_scattering",
                                                    "time_offset"};
  return kCatalog;
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

std::vector<Finding> detect_effects(const SetObservations& obs, BandSummary* summary) {
  const size_t n = obs.meas.size();
  const double fs = obs.measured.empty() ? 16000.0 : obs.measured[0].sample_rate_hz;
  std::vector<Finding> out;

  // ---- time_offset: onset inconsistent with the simulated time of flight.
  Finding offset;
  {
    offset.effect = "time_offset";
    const std::vector<double> d = paired(obs.meas, obs.sim_a, [](const RirFeatures& f) { return f.onset_s * 1e3; });
    const std::vector<double> e = paired(obs.sim_b, obs.sim_a, [](const RirFeatures& f) { return f.onset_s * 1e3; });
    // 0.6 ms = 0.2 m of path: stated positions are rarely better than +-0.1 m per coordinate
    // (up to 0.17 m in distance), and an offset smaller than that is indistinguishable from them.
    const double thr = std::max(kThresholds.time_offset_min_ms, kThresholds.time_offset_null_mads * median_abs_deviation(e));
    auto rule = [&](const std::vector<double>& x, size_t* k, double* p, double* med) {
      std::vector<double> a;
      *k = 0;
      for (double v : x) { a.push_back(std::abs(v)); *k += std::abs(v) > thr; }
      *p = binomial_upper_p(*k, x.size(), kThresholds.time_offset_rirs_rate);
      *med = median_of(a);
      return *p < kThresholds.alpha && *med > thr;
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
                      " ms, median signed " + num(median_of(d)) + " ms; binomial p = " + num(p, 2) +
                      " against a 5 % per-RIR rate); seed-vs-seed median " + num(medn) + " ms.";
  }

  // ---- noise_floor: the decay flattens at a level (stationary noise stops the late decay).
  Finding noise = decide_mean(
      "noise_floor", paired(obs.meas, obs.sim_a, [](const RirFeatures& f) { return f.late_decay_db; }),
      paired(obs.sim_b, obs.sim_a, [](const RirFeatures& f) { return f.late_decay_db; }), kThresholds.noise_floor_min_db, -1,
      "decay over the last 30 % of the file (level at 70-80 % minus 90-100 %, 500 Hz-4 kHz median)", "dB");
  {
    std::vector<double> late;
    for (const RirFeatures& f : obs.meas) late.push_back(f.late_decay_db);
    const double flat = median_of(late);
    if (noise.detected && !(flat < kThresholds.noise_floor_flat_db)) noise.detected = false;
    noise.evidence += " Measured late decay (median over the set) " + num(flat) + " dB; flat below 3 dB is required.";
    if (!noise.detected) noise.confidence = std::min(noise.confidence, 0.49);
  }

  // ---- room_modes: peaks at the predicted mode frequencies.
  Finding modes = decide_mean(
      "room_modes", paired(obs.meas, obs.sim_a, [](const RirFeatures& f) { return f.mode_prominence_db; }),
      paired(obs.sim_b, obs.sim_a, [](const RirFeatures& f) { return f.mode_prominence_db; }), kThresholds.room_modes_min_db, +1,
      "spectrum at the predicted shoebox modes above the spectrum between them (window maxima, each re the local mean level over +-10 Hz)", "dB");

  // ---- diffuse_scattering: early echo density.
  std::vector<double> ed_d, ed_e;
  for (const auto& [x, y] : obs.echo_density_meas_a) ed_d.push_back(x - y);
  for (const auto& [x, y] : obs.echo_density_b_a) ed_e.push_back(x - y);
  Finding scatter = decide_mean("diffuse_scattering", ed_d, ed_e, kThresholds.scattering_min_echo_density, 0,
                                "early (5-45 ms) normalised echo density, 1-4 kHz, cross-equalised", "");

  // ---- transducer_response: the same spectral shape in the direct sound and the tail.
  Finding transducer;
  {
    transducer.effect = "transducer_response";
    std::vector<int> bands;
    for (int b = 0; b < kNumOctaveBands; ++b) {
      if (direct_band_reliable(b, fs)) bands.push_back(b);
    }
    auto shapes = [&](const std::vector<RirFeatures>& x, const std::vector<RirFeatures>& y, bool direct) {
      std::vector<std::vector<double>> s(kNumOctaveBands, std::vector<double>(n, NAN));
      for (size_t i = 0; i < n; ++i) {
        double m = 0.0;
        int c = 0;
        BandValues dlt{};
        for (int b : bands) {
          dlt[b] = direct ? x[i].direct_band_db[b] - y[i].direct_band_db[b] : x[i].tail_band_db[b] - y[i].tail_band_db[b];
          if (std::isfinite(dlt[b])) { m += dlt[b]; ++c; }
        }
        if (c == 0) continue;
        for (int b : bands) s[b][i] = dlt[b] - m / c;
      }
      return s;
    };
    const double t_crit = t_critical(kThresholds.alpha / std::max<size_t>(1, bands.size()), std::max<double>(2.0, n - 1.0));
    auto rule = [&](const std::vector<RirFeatures>& x, const std::vector<RirFeatures>& y, double* max_abs, double* corr,
                    double* p_min, int* worst, BandValues* dshape, BandValues* tshape) {
      const auto ds = shapes(x, y, true), ts = shapes(x, y, false);
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
        if (std::abs(t.mean) > kThresholds.transducer_min_db && std::abs(t.t) > t_crit) any = true;
        *p_min = std::min(*p_min, t.p_two_sided * bands.size());
      }
      *corr = correlation(dm, tm);
      return any && *corr > kThresholds.transducer_min_correlation;
    };
    double mx, corr, pmin, mxn, corrn, pminn;
    int worst, worstn;
    BandValues ds{}, ts{}, dsn{}, tsn{};
    const bool fires = rule(obs.meas, obs.sim_a, &mx, &corr, &pmin, &worst, &ds, &ts);
    const bool null_fires = rule(obs.sim_b, obs.sim_a, &mxn, &corrn, &pminn, &worstn, &dsn, &tsn);
    transducer.detected = fires && !null_fires;
    transducer.statistic = mx;
    transducer.null_statistic = mxn;
    transducer.threshold = kThresholds.transducer_min_db;
    transducer.statistic_unit = "dB";
    transducer.confidence = confidence_of(std::min(1.0, pmin), mx, 1.0, transducer.detected);
    transducer.evidence = "direct-sound spectral shape departs by up to " + num(mx) + " dB" +
                          (worst >= 0 ? " (at " + band_name(worst) + ")" : std::string()) +
                          " from the simulation (threshold 1 dB at |t| > " + num(t_crit) +
                          "), and the tail's shape correlates with it at r = " + num(corr) +
                          " (needs > " + num(kThresholds.transducer_min_correlation) + "); seed-vs-seed " + num(mxn) + " dB, r = " + num(corrn) + ".";
    if (summary) { summary->direct_shape_db = ds; summary->tail_shape_db = ts; }
  }

  // ---- decay rates per band: air_absorption and band_absorption.
  Finding air, band;
  {
    air.effect = "air_absorption";
    band.effect = "band_absorption";
    std::vector<std::vector<double>> q(kNumOctaveBands), qn(kNumOctaveBands);
    BandValues base{};
    std::vector<int> bands;
    double schroeder = median_of(obs.schroeder_hz);
    for (int b = 0; b < kNumOctaveBands; ++b) {
      size_t ok = 0;
      std::vector<double> rates;
      for (size_t i = 0; i < n; ++i) {
        const double rm = obs.meas[i].decay_rate_per_s[b], ra = obs.sim_a[i].decay_rate_per_s[b],
                     rb = obs.sim_b[i].decay_rate_per_s[b];
        q[b].push_back(std::log(rm / ra));
        qn[b].push_back(std::log(rb / ra));
        if (std::isfinite(rm) && std::isfinite(ra) && std::isfinite(rb)) ++ok;
        rates.push_back(ra);
      }
      base[b] = median_of(rates);
      if (n > 0 && ok >= 0.8 * n && ok >= 3) bands.push_back(b);
    }
    const bool modes_claim_low = modes.detected && !obs.room_modes_ruled_out;
    std::vector<int> tested;
    for (int b : bands) {
      if (!(modes_claim_low && kOctaveCentersHz[b] < 2.0 * schroeder)) tested.push_back(b);
    }
    // Rooms (absorption is a property of each room, air of the whole campaign).
    std::map<std::string, std::vector<size_t>> groups;
    for (size_t i = 0; i < n; ++i) groups[room_group(obs.rooms[i])].push_back(i);
    std::map<std::string, BandValues> group_base;
    for (const auto& [g, idx] : groups) {
      for (int b = 0; b < kNumOctaveBands; ++b) {
        std::vector<double> r;
        for (size_t i : idx) r.push_back(obs.sim_a[i].decay_rate_per_s[b]);
        group_base[g][b] = median_of(r);
      }
    }
    const double t_crit = t_critical(kThresholds.alpha / std::max<size_t>(1, tested.size() * groups.size()),
                                     std::max<double>(2.0, n / std::max<double>(1.0, groups.size()) - 1.0));
    const double min_ratio = std::log(kThresholds.band_min_rate_ratio);
    const double temp = obs.rooms.empty() ? 20.0 : obs.rooms[0].temperature_c;
    const double c = obs.rooms.empty() ? 343.0 : obs.rooms[0].speed_of_sound_m_s;

    auto analyse = [&](const std::vector<std::vector<double>>& x, AirFit* fit, bool* air_fires, bool* band_fires,
                       int* worst_band, double* worst_ratio, std::string* worst_room, BandValues* air_curve,
                       double* uniform_chi2) {
      std::vector<RateObservation> observations;
      for (const auto& [g, idx] : groups) {
        if (idx.size() < 3) continue;
        for (int b : tested) {
          std::vector<double> v;
          for (size_t i : idx) v.push_back(x[b][i]);
          const OneSampleTest t = t_test(v);
          if (t.n < 3) continue;
          observations.push_back({b, t.mean, std::max(t.standard_error, 1e-4), group_base[g][b]});
        }
      }
      *fit = fit_air(observations, temp, c);
      // The simpler rival: one decay-rate factor for every band (a room volume or area that
      // differs from the stated one, or absorption off by the same factor everywhere). Air must
      // explain the bands better than that: dry air's ISO curve is nearly flat across the bands
      // and would otherwise take a uniform change for air.
      double sw = 0.0, swx = 0.0;
      for (const RateObservation& o : observations) {
        const double w = 1.0 / (o.standard_error * o.standard_error);
        sw += w;
        swx += w * o.mean_log_ratio;
      }
      double chi2_uniform = 0.0;
      for (const RateObservation& o : observations) {
        chi2_uniform += std::pow((o.mean_log_ratio - (sw > 0.0 ? swx / sw : 0.0)) / o.standard_error, 2);
      }
      *uniform_chi2 = chi2_uniform;
      air_curve->fill(NAN);
      for (int b : tested) (*air_curve)[b] = air_log_ratio(b, *fit, base[b], temp, c);
      bool residual_significant = false, raw_significant = false, raw_significant_air = false;
      *worst_band = -1;
      *worst_ratio = 0.0;
      for (const auto& [g, idx] : groups) {
        if (idx.size() < 3) continue;
        for (int b : tested) {
          const double curve = air_log_ratio(b, *fit, group_base[g][b], temp, c);
          std::vector<double> r, raw;
          for (size_t i : idx) { r.push_back(x[b][i] - curve); raw.push_back(x[b][i]); }
          const OneSampleTest tr = t_test(r), t0 = t_test(raw);
          if (std::abs(tr.mean) > min_ratio && std::abs(tr.t) > t_crit) residual_significant = true;
          if (std::abs(t0.mean) > min_ratio && std::abs(t0.t) > t_crit) raw_significant = true;
          if (std::abs(t0.mean) > std::log(kThresholds.air_min_top_rate_ratio) && std::abs(t0.t) > t_crit) raw_significant_air = true;
          if (std::abs(t0.mean) > std::abs(*worst_ratio)) { *worst_ratio = t0.mean; *worst_band = b; *worst_room = g; }
        }
      }
      const double top = tested.empty() ? 0.0 : (*air_curve)[tested.back()];
      const double min_gain = kThresholds.air_min_chi2_improvement;
      *air_fires = raw_significant_air && fit->scale > 0.0 && fit->chi2_fit < kThresholds.air_max_chi2_fraction * fit->chi2_zero &&
                   fit->chi2_zero - fit->chi2_fit > min_gain && *uniform_chi2 - fit->chi2_fit > min_gain &&
                   !residual_significant && top > std::log(kThresholds.air_min_top_rate_ratio);
      // With air explaining everything, the per-band refit is not needed; otherwise any band
      // that departs (raw, i.e. the refit also absorbs air) is band_absorption.
      *band_fires = *air_fires ? residual_significant : raw_significant;
    };
    AirFit fit, fitn;
    BandValues curve{}, curven{};
    bool air_f, band_f, air_n, band_n;
    int worst, worstn;
    double wr, wrn;
    std::string worst_room, worst_roomn;
    double uniform_chi2 = 0.0, uniform_chi2n = 0.0;
    analyse(q, &fit, &air_f, &band_f, &worst, &wr, &worst_room, &curve, &uniform_chi2);
    analyse(qn, &fitn, &air_n, &band_n, &worstn, &wrn, &worst_roomn, &curven, &uniform_chi2n);
    BandValues mean{};
    for (int b : tested) mean[b] = mean_of(q[b]);
    air.detected = air_f && !air_n;
    band.detected = band_f && !band_n;
    const double top_air = tested.empty() ? 0.0 : curve[tested.back()];
    air.statistic = top_air;
    air.null_statistic = tested.empty() ? 0.0 : curven[tested.back()];
    air.threshold = std::log(kThresholds.air_min_top_rate_ratio);
    air.statistic_unit = "ln(rate ratio)";
    const double p_air = chi_square_upper_p(std::max(0.0, fit.chi2_zero - fit.chi2_fit), 2.0);
    air.confidence = confidence_of(p_air, top_air, std::log(kThresholds.air_min_top_rate_ratio), air.detected);
    std::string per_band;
    for (int b : tested) {
      per_band += (per_band.empty() ? "" : ", ") + band_name(b) + " " + num(100.0 * std::expm1(mean[b]), 2) + "%";
    }
    air.evidence = "decay-rate change per band (measured vs simulated): " + per_band +
                   "; the best ISO 9613-1 curve (humidity " + num(fit.humidity_percent) + " %, scale " + num(fit.scale) +
                   ") reduces chi-square from " + num(fit.chi2_zero) + " to " + num(fit.chi2_fit) +
                   " (one uniform rate factor for all bands: " + num(uniform_chi2) + ")" +
                   " and predicts " + num(100.0 * std::expm1(top_air), 2) + "% faster decay in the top band (needs > 5%, " +
                   "< 10% of chi-square left, 20 below the uniform factor's, and no significant residual band).";
    if (air.detected) {
      air.parameters = {{"humidity_percent", fit.humidity_percent}, {"scale", fit.scale}};
    }
    band.statistic = wr;
    band.null_statistic = wrn;
    band.threshold = min_ratio;
    band.statistic_unit = "ln(rate ratio)";
    band.confidence = confidence_of(std::isfinite(wr) ? student_t_two_sided_p(t_crit, n - 1.0) : 1.0, wr, min_ratio,
                                    band.detected);
    band.evidence = "largest per-band decay-rate departure " + num(100.0 * std::expm1(wr), 2) + "%" +
                    (worst >= 0 ? " at " + band_name(worst) : std::string()) +
                    (groups.size() > 1 ? " in room " + worst_room : std::string()) + " (threshold 8% at |t| > " + num(t_crit) +
                    (air.detected ? ", after the air-absorption fit" : "") + ")" +
                    (modes_claim_low ? "; bands below " + num(2.0 * schroeder) + " Hz are left to room_modes" : "") +
                    "; seed-vs-seed largest " + num(100.0 * std::expm1(wrn), 2) + "%.";
    if (summary) {
      for (int b = 0; b < kNumOctaveBands; ++b) {
        const OneSampleTest t = t_test(q[b]);
        summary->mean_log_rate_ratio[b] = t.n ? t.mean : NAN;
        summary->se_log_rate_ratio[b] = t.n ? t.standard_error : NAN;
        summary->air_fit_log_ratio[b] = curve[b];
        const OneSampleTest l =
            t_test(paired(obs.meas, obs.sim_a, [b](const RirFeatures& f) { return f.level_db[b]; }));
        summary->mean_level_delta_db[b] = l.n ? l.mean : NAN;
        summary->se_level_delta_db[b] = l.n ? l.standard_error : NAN;
      }
    }
  }

  for (const std::string& id : effect_catalog()) {
    if (id == "room_modes") out.push_back(modes);
    if (id == "air_absorption") out.push_back(air);
    if (id == "band_absorption") out.push_back(band);
    if (id == "transducer_response") out.push_back(transducer);
    if (id == "noise_floor") out.push_back(noise);
    if (id == "diffuse_scattering") out.push_back(scatter);
    if (id == "time_offset") out.push_back(offset);
  }
  return out;
}

}  // namespace tsrir::diagnose
