#include "fidelity_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "fidelity_domains.h"

namespace tsrir_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Biquad {
  double b0, b1, b2, a1, a2;
};

// 4th-order Butterworth as two biquads (bilinear transform, Q = 0.5412 and 1.3066).
std::vector<Biquad> butterworth4(double cutoff_hz, double fs, bool high_pass) {
  std::vector<Biquad> sections;
  for (double q : {0.54119610, 1.30656296}) {
    const double w0 = 2 * M_PI * cutoff_hz / fs, c = std::cos(w0), alpha = std::sin(w0) / (2 * q);
    const double a0 = 1 + alpha;
    Biquad b;
    if (high_pass) {
      b.b0 = (1 + c) / 2 / a0, b.b1 = -(1 + c) / a0, b.b2 = (1 + c) / 2 / a0;
    } else {
      b.b0 = (1 - c) / 2 / a0, b.b1 = (1 - c) / a0, b.b2 = (1 - c) / 2 / a0;
    }
    b.a1 = -2 * c / a0, b.a2 = (1 - alpha) / a0;
    sections.push_back(b);
  }
  return sections;
}

void run_biquads(std::vector<double>& x, const std::vector<Biquad>& sections) {
  for (const Biquad& s : sections) {
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    for (double& v : x) {
      const double y = s.b0 * v + s.b1 * x1 + s.b2 * x2 - s.a1 * y1 - s.a2 * y2;
      x2 = x1, x1 = v, y2 = y1, y1 = y, v = y;
    }
  }
}

// Zero-phase (forward-backward) filtering, so the direct sound stays where it is.
std::vector<double> filtered(const tsrir::Signal& rir, double cutoff_hz, bool high_pass) {
  std::vector<double> x(rir.samples.begin(), rir.samples.end());
  const auto sections = butterworth4(cutoff_hz, rir.sample_rate_hz, high_pass);
  run_biquads(x, sections);
  std::reverse(x.begin(), x.end());
  run_biquads(x, sections);
  std::reverse(x.begin(), x.end());
  return x;
}

long onset_sample(const tsrir::Signal& rir) {
  float peak = 0;
  for (float v : rir.samples) peak = std::max(peak, std::abs(v));
  for (size_t k = 0; k < rir.samples.size(); ++k) {
    if (std::abs(rir.samples[k]) >= 0.1f * peak) return long(k);
  }
  return 0;
}

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

double mean(const std::vector<double>& v) {
  return v.empty() ? kNaN : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    for (size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * double(i + j);  // ties: mean rank
    i = j + 1;
  }
  return r;
}

}  // namespace

RirFidelityMeasures measure_fidelity_rir(const tsrir::Signal& rir) {
  RirFidelityMeasures m;
  const double fs = rir.sample_rate_hz;
  const long onset = onset_sample(rir);
  m.onset_ms = 1000.0 * double(onset) / fs;
  const std::vector<double> low = filtered(rir, kEffectMaxHz, false);
  const std::vector<double> high = filtered(rir, kAcousticsMinHz, true);
  double e_low = 0, e_high = 0;
  for (double v : low) e_low += v * v;
  for (double v : high) e_high += v * v;
  m.effect_db = 10 * std::log10((e_low + 1e-30) / (e_high + 1e-30));

  const long direct_end = std::min<long>(long(high.size()), onset + long(std::lround(0.0025 * fs)));
  double direct = 0, late = 0;
  for (long k = std::max<long>(0, onset - long(std::lround(0.001 * fs))); k < direct_end; ++k) direct += high[k] * high[k];
  for (size_t k = size_t(direct_end); k < high.size(); ++k) late += high[k] * high[k];
  m.drr_db = 10 * std::log10((direct + 1e-30) / (late + 1e-30));

  // Schroeder backward integral of the reverberant part (after the direct sound's window, so a
  // strong direct sound does not steepen the fit); T20 fit by least squares.
  std::vector<double> edc(high.size() - size_t(direct_end));
  double acc = 0;
  for (size_t k = high.size(); k-- > size_t(direct_end);) {
    acc += high[k] * high[k];
    edc[k - size_t(direct_end)] = acc;
  }
  m.t60_s = kNaN;
  if (acc > 0) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    bool reached = false;
    for (size_t k = 0; k < edc.size(); ++k) {
      const double db = 10 * std::log10(edc[k] / acc + 1e-300);
      if (db < -25) {
        reached = true;
        break;
      }
      if (db <= -5) {
        const double t = double(k) / fs;
        sx += t, sy += db, sxx += t * t, sxy += t * db, ++n;
      }
    }
    const double slope = n > 1 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0;
    if (reached && slope < 0) m.t60_s = -60.0 / slope;
  }
  return m;
}

std::vector<double> early_log_envelope(const tsrir::Signal& rir, long start_sample) {
  const std::vector<double> high = filtered(rir, kAcousticsMinHz, true);
  const double fs = rir.sample_rate_hz;
  const long frame = long(std::lround(0.001 * fs));
  const long begin = start_sample + 2 * frame, end = start_sample + 200 * frame;
  std::vector<double> env;
  for (long f = begin; f + frame <= end && f + frame <= long(high.size()); f += frame) {
    double e = 0;
    for (long k = f; k < f + frame; ++k) e += high[k] * high[k];
    env.push_back(10 * std::log10(e + 1e-20));
  }
  // Remove the least-squares line.
  const double n = double(env.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < env.size(); ++i) sx += double(i), sy += env[i], sxx += double(i) * i, sxy += double(i) * env[i];
  const double denom = n * sxx - sx * sx;
  const double slope = denom > 0 ? (n * sxy - sx * sy) / denom : 0, icept = n > 0 ? (sy - slope * sx) / n : 0;
  for (size_t i = 0; i < env.size(); ++i) env[i] -= icept + slope * double(i);
  return env;
}

std::vector<double> low_band_addition(const tsrir::Signal& input, const tsrir::Signal& output, long start_sample) {
  auto peak = [](const tsrir::Signal& x) {
    float p = 0;
    for (float v : x.samples) p = std::max(p, std::abs(v));
    return p > 0 ? double(p) : 1.0;
  };
  const double in_peak = peak(input), out_peak = peak(output);
  tsrir::Signal added = input;
  added.samples.assign(input.samples.size(), 0.0f);
  const size_t n = std::min(input.samples.size(), output.samples.size());
  for (size_t k = 0; k < n; ++k) {
    added.samples[k] = float(output.samples[k] / out_peak - input.samples[k] / in_peak);
  }
  const std::vector<double> low = filtered(added, 200.0, false);
  const long begin = std::max(0L, start_sample);
  const long end = std::min(long(low.size()), begin + long(std::lround(0.2 * input.sample_rate_hz)));
  return begin < end ? std::vector<double>(low.begin() + begin, low.begin() + end) : std::vector<double>();
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = std::min(a.size(), b.size());
  if (n < 2) return kNaN;
  double ma = 0, mb = 0;
  for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= double(n), mb /= double(n);
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb), saa += (a[i] - ma) * (a[i] - ma), sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  return pearson(ranks(a), ranks(b));
}

std::string FidelityReport::summary() const {
  std::ostringstream os;
  os.precision(3);
  os << "n " << count << "; effect dB: synthetic " << synthetic_effect_db << ", real " << real_effect_db
     << ", translated " << translated_effect_db << " (moved " << moved << " of the gap)"
     << "; T60 spearman " << t60_spearman << ", median rel. error " << t60_median_relative_error
     << " (" << unmeasurable_t60 << " unmeasurable)"
     << "; DRR spearman " << drr_spearman << ", median error " << drr_median_error_db << " dB"
     << "; onset within 1 ms " << onset_fraction_within << " (max error " << onset_max_error_ms << " ms)"
     << "; early envelope corr. own " << own_correlation << ", other " << other_correlation
     << "; added <200 Hz corr. across RIRs " << added_correlation
     << "; " << (passed() ? "PASS" : "FAIL");
  for (const auto& f : failures) os << " [" << f << "]";
  return os.str();
}

FidelityReport evaluate_fidelity(const std::vector<tsrir::Signal>& inputs,
                                 const std::vector<tsrir::Signal>& outputs,
                                 const std::vector<tsrir::Signal>& real, const FidelityBounds& bounds) {
  FidelityReport r;
  const size_t n = std::min(inputs.size(), outputs.size());
  r.count = int(n);
  std::vector<double> in_effect, out_effect, real_effect, in_t60, out_t60, t60_error, in_drr, out_drr, drr_error;
  int onset_ok = 0;
  std::vector<std::vector<double>> in_env(n), out_env(n), added(n);
  for (size_t i = 0; i < n; ++i) {
    const RirFidelityMeasures a = measure_fidelity_rir(inputs[i]), b = measure_fidelity_rir(outputs[i]);
    in_effect.push_back(a.effect_db);
    out_effect.push_back(b.effect_db);
    if (std::isfinite(a.t60_s) && std::isfinite(b.t60_s)) {
      in_t60.push_back(a.t60_s), out_t60.push_back(b.t60_s);
      t60_error.push_back(std::abs(b.t60_s - a.t60_s) / a.t60_s);
    } else {
      ++r.unmeasurable_t60;
    }
    in_drr.push_back(a.drr_db), out_drr.push_back(b.drr_db), drr_error.push_back(std::abs(b.drr_db - a.drr_db));
    const double onset_error = std::abs(b.onset_ms - a.onset_ms);
    r.onset_max_error_ms = std::max(r.onset_max_error_ms, onset_error);
    if (onset_error <= bounds.max_onset_error_ms) ++onset_ok;
    {
      std::ostringstream line;
      line.precision(3);
      line << inputs[i].id << ": effect " << a.effect_db << " -> " << b.effect_db << " dB, T60 " << a.t60_s << " -> "
           << b.t60_s << " s, DRR " << a.drr_db << " -> " << b.drr_db << " dB, onset " << a.onset_ms << " -> "
           << b.onset_ms << " ms\n";
      r.per_rir += line.str();
    }
    const long start = long(std::lround(a.onset_ms * inputs[i].sample_rate_hz / 1000.0));
    in_env[i] = early_log_envelope(inputs[i], start);
    out_env[i] = early_log_envelope(outputs[i], start);
    added[i] = low_band_addition(inputs[i], outputs[i], start);
  }
  for (const auto& rir : real) real_effect.push_back(measure_fidelity_rir(rir).effect_db);
  r.synthetic_effect_db = mean(in_effect), r.translated_effect_db = mean(out_effect);
  r.real_effect_db = mean(real_effect);
  r.moved = (r.translated_effect_db - r.synthetic_effect_db) / (r.real_effect_db - r.synthetic_effect_db);
  // A T60 that the output lost counts as an error of 1 (100%).
  for (int k = 0; k < r.unmeasurable_t60; ++k) t60_error.push_back(1.0);
  r.t60_spearman = spearman(in_t60, out_t60), r.t60_median_relative_error = median(t60_error);
  r.drr_spearman = spearman(in_drr, out_drr), r.drr_median_error_db = median(drr_error);
  r.onset_fraction_within = n ? double(onset_ok) / double(n) : 0;
  std::vector<double> own, other;
  for (size_t i = 0; i < n; ++i) {
    own.push_back(pearson(out_env[i], in_env[i]));
    for (size_t j = 0; j < n; ++j) {
      if (j != i) other.push_back(pearson(out_env[i], in_env[j]));
    }
  }
  r.own_correlation = mean(own), r.other_correlation = mean(other);
  std::vector<double> pairs;
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      pairs.push_back(pearson(added[i], added[j]));  // over the shorter of the two
    }
  }
  r.added_correlation = mean(pairs);

  auto fail = [&](bool bad, const std::string& what) {
    if (bad) r.failures.push_back(what);
  };
  std::ostringstream b;
  fail(!(r.moved >= bounds.min_moved && r.moved <= bounds.max_moved), "effect moved outside [0.5, 1.5] of the gap");
  fail(!(r.t60_spearman >= bounds.min_t60_spearman), "T60 spearman < 0.8");
  fail(!(r.t60_median_relative_error <= bounds.max_t60_median_relative_error), "T60 median relative error > 0.2");
  fail(!(r.drr_spearman >= bounds.min_drr_spearman), "DRR spearman < 0.7");
  fail(!(r.onset_fraction_within >= bounds.min_onset_fraction), "fewer than 90% of onsets within 1 ms");
  fail(!(r.own_correlation - r.other_correlation >= bounds.min_own_minus_other),
       "own-input minus other-input envelope correlation < 0.3");
  fail(!(r.added_correlation <= bounds.max_added_correlation),
       "below-200 Hz additions correlate > 0.5 across RIRs (one template)");
  return r;
}

}  // namespace tsrir_test
