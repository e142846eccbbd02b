#include "diagnose/unexplained.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "diagnose/decision_rules.h"
#include "diagnose/extension_fit.h"
#include "diagnose/set_statistics.h"
#include "dsp/octave_filter.h"
#include "util/parallel.h"

namespace tsrir::diagnose {
namespace {

constexpr std::array<int, 4> kShapeBands = {3, 4, 5, 6};      // 500 Hz .. 4 kHz
constexpr std::array<double, 8> kShapeTimesMs = {50.0, 100.0, 150.0, 200.0, 300.0, 400.0, 500.0, 600.0};

// The views of one response (measured or rendered), from its onset.
struct Views {
  std::array<std::array<double, kShapeTimesMs.size()>, kShapeBands.size()> edc_db{};  // per band, at kShapeTimesMs (NaN past the active part)
  double periodicity = NAN, periodicity_lag_ms = NAN;
  std::vector<double> early;  // energy per 0.5 ms bin, 3-40 ms after the onset
  // Per shape band: the early (EDT) and late (T30, else T20) decay rates, 1/s (NaN: not measured).
  std::array<double, kShapeBands.size()> early_rate{}, late_rate{};
};

double db(double x) { return x > 0.0 ? 10.0 * std::log10(x) : NAN; }

void decay_shape_view(const Signal& s, size_t onset, size_t end, Views* v) {
  const double fs = s.sample_rate_hz;
  for (size_t k = 0; k < kShapeBands.size(); ++k) {
    v->edc_db[k].fill(NAN);
    if (octave_upper_edge_hz(kOctaveCentersHz[kShapeBands[k]]) >= 0.5 * fs) continue;
    const std::vector<double> y = sos_filter(ansi_octave_filter(kOctaveCentersHz[kShapeBands[k]], fs, 3), s.samples);
    std::vector<double> tail(end + 1, 0.0);
    for (size_t i = end; i-- > onset;) tail[i] = tail[i + 1] + y[i] * y[i];
    for (size_t t = 0; t < kShapeTimesMs.size(); ++t) {
      const size_t i = onset + static_cast<size_t>(kShapeTimesMs[t] * 1e-3 * fs);
      if (i < end) v->edc_db[k][t] = db(tail[i] / tail[onset]);
    }
  }
}

void periodicity_view(const Signal& s, size_t onset, size_t end, Views* v) {
  const double fs = s.sample_rate_hz;
  const std::vector<double> y =
      sos_filter(butterworth_bandpass(2, 1000.0, std::min(6000.0, 0.45 * fs), fs), s.samples);
  const size_t bin = std::max<size_t>(1, static_cast<size_t>(0.0005 * fs));
  const size_t a = onset + static_cast<size_t>(0.08 * fs), b = std::min(end, onset + static_cast<size_t>(0.6 * fs));
  std::vector<double> e;
  for (size_t i = a; i + bin <= b; i += bin) {
    double x = 0.0;
    for (size_t j = i; j < i + bin; ++j) x += y[j] * y[j];
    e.push_back(x);
  }
  const size_t half = 20;  // a 20 ms moving average (40 bins of 0.5 ms) is the decay trend
  if (e.size() < 8 * half) return;
  std::vector<double> x(e.size(), 0.0);
  for (size_t i = 0; i < e.size(); ++i) {
    const size_t lo = i >= half ? i - half : 0, hi = std::min(e.size(), i + half + 1);
    double m = 0.0;
    for (size_t j = lo; j < hi; ++j) m += e[j];
    m /= static_cast<double>(hi - lo);
    x[i] = m > 0.0 ? e[i] / m - 1.0 : 0.0;
  }
  double norm = 0.0;
  for (double w : x) norm += w * w;
  if (!(norm > 0.0)) return;
  for (size_t lag = 20; lag <= 120 && lag < x.size(); ++lag) {  // 10-60 ms
    double r = 0.0;
    for (size_t i = 0; i + lag < x.size(); ++i) r += x[i] * x[i + lag];
    r /= norm;
    if (!(r <= v->periodicity)) {
      v->periodicity = r;
      v->periodicity_lag_ms = 0.5 * lag;
    }
  }
}

void early_pattern_view(const Signal& s, size_t onset, Views* v) {
  const size_t bin = std::max<size_t>(1, static_cast<size_t>(0.0005 * s.sample_rate_hz));
  for (size_t k = 6; k < 80; ++k) {
    double e = 0.0;
    for (size_t i = onset + k * bin; i < onset + (k + 1) * bin && i < s.size(); ++i) e += double(s.samples[i]) * s.samples[i];
    v->early.push_back(e);
  }
}

// Prominence (dB) of the early envelope's bin k over its local median (+-3 ms), the largest of
// bins k-1..k+1 (a reflection a position error moves by up to ~0.3 ms still counts).
double prominence_db(const std::vector<double>& e, size_t k) {
  double best = -INFINITY;
  for (size_t j = k > 0 ? k - 1 : 0; j <= k + 1 && j < e.size(); ++j) {
    std::vector<double> local;
    for (size_t i = j >= 6 ? j - 6 : 0; i <= j + 6 && i < e.size(); ++i) local.push_back(e[i]);
    const double med = median_of(local);
    if (med > 0.0 && e[j] > 0.0) best = std::max(best, 10.0 * std::log10(e[j] / med));
  }
  return best;
}

// The kPatternPeaks largest local maxima of an early envelope (its specular reflections).
constexpr size_t kPatternPeaks = 8;
std::vector<size_t> strongest_peaks(const std::vector<double>& e) {
  std::vector<size_t> peaks;
  for (size_t k = 1; k + 1 < e.size(); ++k) {
    if (e[k] > e[k - 1] && e[k] >= e[k + 1]) peaks.push_back(k);
  }
  std::sort(peaks.begin(), peaks.end(), [&](size_t a, size_t b) { return e[a] > e[b]; });
  if (peaks.size() > kPatternPeaks) peaks.resize(kPatternPeaks);
  return peaks;
}

// How much less prominent x's envelope is at the model's reflections than at its own strongest
// ones (dB): ~0 when its reflections arrive where the model's do, however strong they are (heavy
// scattering weakens both alike); large when they arrive elsewhere (a room of another shape).
double pattern_loss_db(const Views& x, const Views& model) {
  if (x.early.size() != model.early.size() || x.early.empty()) return NAN;
  double own = 0.0, at_model = 0.0;
  const std::vector<size_t> own_peaks = strongest_peaks(x.early), model_peaks = strongest_peaks(model.early);
  if (own_peaks.empty() || model_peaks.empty()) return NAN;
  for (size_t k : own_peaks) own += prominence_db(x.early, k) / own_peaks.size();
  for (size_t k : model_peaks) at_model += prominence_db(x.early, k) / model_peaks.size();
  return own - at_model;
}

Views views_of(const Signal& s, const RirFeatures& f) {
  Views v;
  const size_t onset = static_cast<size_t>(std::max(0.0, f.onset_s * s.sample_rate_hz));
  const size_t end = std::min(s.size(), static_cast<size_t>(std::lround(f.active_end_s * s.sample_rate_hz)));
  if (onset >= end) return v;
  decay_shape_view(s, onset, end, &v);
  periodicity_view(s, onset, end, &v);
  early_pattern_view(s, onset, &v);
  return v;
}

// The two-slopes view's decay rates, from the feature pass.
Views with_rates(Views v, const RirFeatures& f) {
  for (size_t k = 0; k < kShapeBands.size(); ++k) {
    v.early_rate[k] = f.early_decay_rate_per_s[kShapeBands[k]];
    v.late_rate[k] = f.decay_rate_per_s[kShapeBands[k]];
  }
  return v;
}

// The bend of band k's decay departure D(t) = EDC_x(t) - EDC_y(t), dB: how far D sags below its
// chord from 50 ms to the last time both are measured (the largest sag; negative for a bulge). A
// wrong decay rate makes D a straight line (no bend); a double slope (faster first, slower later)
// or a late floor make it sag.
double bend_departure(const Views& x, const Views& y, size_t k) {
  std::vector<double> t, dep;
  for (size_t j = 0; j < kShapeTimesMs.size(); ++j) {
    const double dj = x.edc_db[k][j] - y.edc_db[k][j];
    if (!std::isfinite(dj)) break;
    t.push_back(kShapeTimesMs[j]);
    dep.push_back(dj);
  }
  if (t.size() < 3) return NAN;
  double sag = 0.0;
  for (size_t j = 1; j + 1 < t.size(); ++j) {
    const double chord = dep.front() + (dep.back() - dep.front()) * (t[j] - t.front()) / (t.back() - t.front());
    if (std::abs(chord - dep[j]) > std::abs(sag)) sag = chord - dep[j];
  }
  return sag;
}

// The decay-shape bands (indices into kShapeBands) whose own early decay rate (EDT, the set's
// median) is within kMaxNeighbourRateRatio of both neighbouring octaves'. A band next to a much
// more slowly decaying one measures a double slope from its filter's leakage alone (its EDT is its
// own decay, its late EDC the neighbour's), and the refit of a large per-band absorption error
// (the tests' draws: factors 0.55-2.5 per band) leaves that bend in the departure: 4.0-5.5 dB,
// as much as a coupled volume's (docs/results/diagnose_power.md). A coupled volume slows every
// band alike, so its bands stay.
constexpr double kMaxNeighbourRateRatio = 1.5;
std::vector<size_t> bands_without_slow_neighbour(const SetObservations& obs) {
  std::array<double, kNumOctaveBands> rate{};
  for (int b = 0; b < kNumOctaveBands; ++b) {
    rate[b] = median_of(obs.each([b](const RirObservation& r) { return r.meas.early_decay_rate_per_s[b]; }));
  }
  std::vector<size_t> kept;
  for (size_t k = 0; k < kShapeBands.size(); ++k) {
    const int b = kShapeBands[k];
    bool slow_neighbour = false;
    for (int nb : {b - 1, b + 1}) {
      if (nb >= 0 && nb < kNumOctaveBands && std::isfinite(rate[nb]) && rate[nb] * kMaxNeighbourRateRatio < rate[b]) slow_neighbour = true;
    }
    if (!slow_neighbour) kept.push_back(k);
  }
  return kept;
}

// Band k's early-vs-late departure: ln(x's early rate / y's) - ln(x's late rate / y's). A wrong
// decay rate (an absorption error, with or without its refit) changes both alike: ~0. A double
// slope that a single-exponential model is fitted to (band_absorption refits the late rate) leaves
// x's early decay faster than y's: positive, ln 2 where the first 10 dB fall twice as fast.
double early_late_departure(const Views& x, const Views& y, size_t k) {
  const double xe = x.early_rate[k], ye = y.early_rate[k], xl = x.late_rate[k], yl = y.late_rate[k];
  if (!(xe > 0.0 && ye > 0.0 && xl > 0.0 && yl > 0.0)) return NAN;
  return std::log(xe / ye) - std::log(xl / yl);
}

// One cell per band of `bands`: f(measured, model A) per RIR, and the null f(model B, model A).
template <typename F>
void band_cells(const std::vector<Views>& m, const std::vector<Views>& a, const std::vector<Views>& b,
                const std::vector<size_t>& bands, F f, std::vector<std::vector<double>>* d, std::vector<std::vector<double>>* e) {
  d->assign(bands.size(), {});
  e->assign(bands.size(), {});
  for (size_t i = 0; i < m.size(); ++i) {
    for (size_t c = 0; c < bands.size(); ++c) {
      (*d)[c].push_back(f(m[i], a[i], bands[c]));
      (*e)[c].push_back(f(b[i], a[i], bands[c]));
    }
  }
}

struct ViewDecision {
  bool departs = false;
  double worst_ratio = 0.0;  // |mean| / threshold of the cell that departs most
  std::string evidence;
  std::vector<std::pair<std::string, double>> where;
};

// One view's cells (paired differences d, null e), decided like a catalog effect: some cell's mean
// beyond min_effect in the direction `sign` at p < alpha / cells, and the null's does not.
ViewDecision decide_cells(const std::vector<std::vector<double>>& d, const std::vector<std::vector<double>>& e,
                          double min_effect, int sign) {
  ViewDecision out;
  const double alpha = kDecision.alpha / std::max<size_t>(1, d.size());
  bool null_fires = false;
  size_t worst = 0;
  for (size_t c = 0; c < d.size(); ++c) {
    const OneSampleTest t = t_test(d[c]), tn = t_test(e[c]);
    auto fires = [&](const OneSampleTest& x) {
      return x.n >= 3 && x.p_two_sided < alpha && std::abs(x.mean) > min_effect && (sign == 0 || x.mean * sign > 0);
    };
    null_fires = null_fires || fires(tn);
    const double ratio = (sign == 0 ? std::abs(t.mean) : sign * t.mean) / min_effect;
    if (ratio > out.worst_ratio || c == 0) { out.worst_ratio = ratio; worst = c; }
    out.departs = out.departs || fires(t);
  }
  out.departs = out.departs && !null_fires;
  out.where.push_back({"cell", static_cast<double>(worst)});
  return out;
}

}  // namespace

std::string residual_view_name(ResidualView view) {
  switch (view) {
    case ResidualView::kDecayShape: return "decay shape";
    case ResidualView::kTwoSlopes: return "two slopes";
    case ResidualView::kLatePeriodicity: return "late periodicity";
    case ResidualView::kEarlyPattern: return "early pattern";
  }
  return "?";
}

UnexplainedCheck check_unexplained(const SetObservations& obs, const std::map<std::string, std::string>& model_by_room,
                                   const DiagnoseOptions& options) {
  const size_t n = obs.size();
  std::vector<Views> m(n), a(n), b(n);
  parallel_for(n, options.num_threads, [&](size_t i) {
    const RirObservation& r = obs[i];
    const std::string& spec = model_by_room.at(room_group(r.room));
    const Signal sa = render_rir(spec, r.room, options.sample_rate_hz, r.measured.size(), options.seed);
    const Signal sb = render_rir(spec, r.room, options.sample_rate_hz, r.measured.size(), options.seed + 1);
    const RirFeatures fa = r.features_of(sa), fb = r.features_of(sb);
    m[i] = with_rates(views_of(r.measured, r.meas), r.meas);
    a[i] = with_rates(views_of(sa, fa), fa);
    b[i] = with_rates(views_of(sb, fb), fb);
  });
  UnexplainedCheck out;
  const UnexplainedThresholds& thr = kUnexplainedThresholds;
  // Decay shape: one cell per band whose octave filter does not mix in a much slower neighbour.
  const std::vector<size_t> shape_bands = bands_without_slow_neighbour(obs);
  std::vector<std::vector<double>> d, e;
  band_cells(m, a, b, shape_bands, bend_departure, &d, &e);
  // One-sided: the measurement's decay bends more than the model's (a double slope, a floor the
  // model lacks). The other way round is the model's own octave leakage (a fast band next to a slow
  // one measures convex in the simulation), which catalog sets with a per-band absorption error show.
  const ViewDecision shape = decide_cells(d, e, thr.min_bend_db, +1);
  const size_t cell = static_cast<size_t>(shape.where.front().second);
  const size_t band = shape_bands.empty() ? 0 : shape_bands[cell];
  const double bend = shape_bands.empty() ? NAN : mean_of(d[cell]);
  // Early vs late decay, the same bands: the measurement's early decay faster than the model's
  // beyond what its late decay is (a double slope the model's single exponential was refitted to).
  std::vector<std::vector<double>> sd, se;
  band_cells(m, a, b, shape_bands, early_late_departure, &sd, &se);
  const ViewDecision slopes = decide_cells(sd, se, thr.min_early_late_log_ratio, +1);
  const size_t slope_band = shape_bands.empty() ? 0 : shape_bands[static_cast<size_t>(slopes.where.front().second)];
  const double slope_log_ratio = shape_bands.empty() ? NAN : mean_of(sd[static_cast<size_t>(slopes.where.front().second)]);
  // Late periodicity: one cell.
  std::vector<std::vector<double>> pd(1), pe(1), lag(1);
  for (size_t i = 0; i < n; ++i) {
    pd[0].push_back(m[i].periodicity - a[i].periodicity);
    pe[0].push_back(b[i].periodicity - a[i].periodicity);
    lag[0].push_back(m[i].periodicity_lag_ms);
  }
  const ViewDecision periodic = decide_cells(pd, pe, thr.min_periodicity, +1);
  // Early pattern: one cell, the pattern loss of the measurement re model A minus that of model B.
  std::vector<std::vector<double>> ed(1), ee(1);
  std::vector<double> loss_m, loss_b;
  for (size_t i = 0; i < n; ++i) {
    loss_m.push_back(pattern_loss_db(m[i], a[i]));
    loss_b.push_back(pattern_loss_db(b[i], a[i]));
    ed[0].push_back(loss_m.back() - loss_b.back());
    ee[0].push_back(0.0);
  }
  const ViewDecision early = decide_cells(ed, ee, thr.min_pattern_loss_db, +1);

  const std::string band_label = band_name(kShapeBands[band]);
  out.evidence = "decay shape: the measured energy decay curve at " + band_label + " sags " + num(bend) +
                 " dB below the straight line a decay-rate error would give, re the model's (50-600 ms after the onset; "
                 "threshold " + num(thr.min_bend_db) + " dB)" + (shape.departs ? " DEPARTS" : "") +
                 "; two slopes: at " + band_name(kShapeBands[slope_band]) + " the measured early decay (EDT) is " +
                 num(std::exp(slope_log_ratio)) + "x faster re the model's than its late decay (T30) is (threshold " +
                 num(std::exp(thr.min_early_late_log_ratio)) + "x)" + (slopes.departs ? " DEPARTS" : "") +
                 "; late periodicity: the 1-6 kHz envelope (80-600 ms) repeats at r = " + num(mean_of(pd[0])) +
                 " above the model's (median lag " + num(median_of(lag[0])) + " ms; threshold " + num(thr.min_periodicity) +
                 ")" + (periodic.departs ? " DEPARTS" : "") + "; early pattern: the measured 3-40 ms envelope is " + num(mean_of(loss_m)) +
                 " dB less prominent at the model's 8 strongest reflections than at its own (the model's second seed: " +
                 num(mean_of(loss_b)) + " dB; threshold " + num(thr.min_pattern_loss_db) + " dB)" +
                 (early.departs ? " DEPARTS" : "") + ".";
  if (shape.departs) out.departing.push_back(ResidualView::kDecayShape);
  if (slopes.departs) out.departing.push_back(ResidualView::kTwoSlopes);
  if (periodic.departs) out.departing.push_back(ResidualView::kLatePeriodicity);
  if (early.departs) out.departing.push_back(ResidualView::kEarlyPattern);
  // Each view's largest departure, departing or not (where and how far).
  out.parameters = {{"decay_bend_db", bend},
                    {"decay_bend_band_hz", kOctaveCentersHz[kShapeBands[band]]},
                    {"early_late_rate_ratio", std::exp(slope_log_ratio)},
                    {"early_late_band_hz", kOctaveCentersHz[kShapeBands[slope_band]]},
                    {"periodicity", mean_of(pd[0])},
                    {"periodicity_lag_ms", median_of(lag[0])},
                    {"early_pattern_loss_db", mean_of(ed[0])}};
  out.statistic = std::max({shape.worst_ratio, slopes.worst_ratio, periodic.worst_ratio, early.worst_ratio});
  return out;
}

}  // namespace tsrir::diagnose
