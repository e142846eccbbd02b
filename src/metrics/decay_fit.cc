#include "metrics/decay_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include "util/cpu_clones.h"

namespace tsrir {

std::vector<double> backward_integral(const double* energy, size_t n, double tail_energy) {
  std::vector<double> edc(n);
  double acc = tail_energy;
  for (size_t i = n; i-- > 0;) {
    acc += energy[i];
    edc[i] = acc;
  }
  return edc;
}

size_t first_index_at_or_below(const double* edc, size_t n, double level) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (edc[mid] <= level) hi = mid; else lo = mid + 1;
  }
  return lo;
}

double DecayFit::decay_time_s() const {
  if (!ok || !(slope_db_per_s < 0)) return std::numeric_limits<double>::quiet_NaN();
  return -60.0 / slope_db_per_s;
}

// The AVX2 clone runs the same operations four wide (no FMA: the target does not enable it, so
// every value is rounded as in the default clone): the same dB values to the bit, in half the time;
// the AVX-512F clone eight wide (its FMA kept out, cpu_clones.h), in half that again.
TSRIR_WIDE_CLONES
void energy_to_db(const double* x, size_t n, double* db) {
  for (size_t i = 0; i < n; ++i) db[i] = normal_energy_to_db(x[i]);
  // Zeros, subnormals, infinities and NaN are rare: patch them with the library call. A vector
  // check (blends, no branch) finds whether there are any.
  constexpr double kMin = std::numeric_limits<double>::min(), kMax = std::numeric_limits<double>::max();
  double normal = 1.0;
  for (size_t i = 0; i < n; ++i) normal = (x[i] >= kMin && x[i] <= kMax) ? normal : 0.0;
  if (normal == 1.0) return;
  for (size_t i = 0; i < n; ++i) {
    if (!(x[i] >= kMin && x[i] <= kMax)) db[i] = 10.0 * std::log10(x[i]);
  }
}

namespace {

struct FitRange {
  bool ok = false;
  size_t first = 0, last = 0;
};

FitRange find_fit_range(const double* edc, size_t usable_end, double reference, double upper_db, double lower_db) {
  FitRange r;
  if (!(reference > 0) || usable_end == 0 || !(upper_db > lower_db)) return r;
  const double upper = reference * std::pow(10.0, upper_db / 10.0);
  const double lower = reference * std::pow(10.0, lower_db / 10.0);
  const size_t first = first_index_at_or_below(edc, usable_end, upper);
  const size_t below = first_index_at_or_below(edc, usable_end, lower);
  // The lower limit must be crossed inside the measured part of the curve.
  if (below >= usable_end || below < first + 3) return r;
  r.ok = true;
  r.first = first;
  r.last = below - 1;
  return r;
}

// The line from the sums of line_fit over m samples from `first`.
DecayFit fit_from_sums(double sy, double sxy, size_t first, size_t m, double fs) {
  DecayFit fit;
  const double xc = 0.5 * (double)(m - 1);
  const double sxx = (double)m * ((double)m * m - 1.0) / 12.0;
  const double slope_per_sample = sxy / sxx;
  const double mean_y = sy / (double)m;
  fit.ok = true;
  fit.first = first;
  fit.last = first + m - 1;
  fit.slope_db_per_s = slope_per_sample * fs;
  fit.intercept_db = mean_y - slope_per_sample * ((double)first + xc);
  return fit;
}

// Least squares of db[i] - ref_db against i / fs for i in [first, last]; db indexed from first.
DecayFit line_fit(const double* db, size_t first, size_t last, double reference, double fs) {
  const size_t m = last - first + 1;
  const double ref_db = 10.0 * std::log10(reference);
  // Centred sums in sample units keep the normal equations well conditioned.
  const double xc = 0.5 * (double)(m - 1);
  double sy = 0, sxy = 0;
  for (size_t i = 0; i < m; ++i) {
    const double y = db[i] - ref_db;
    sy += y;
    sxy += ((double)i - xc) * y;
  }
  return fit_from_sums(sy, sxy, first, m, fs);
}

// Adds the terms [k0, k1) of F line fits in lockstep (their sums in registers): y[f] = the fit's
// dB values from its first sample, xc[f] its centre; the terms are line_fit's.
template <int F>
void add_fit_terms(const double* const* y, double ref_db, const double* xc, size_t k0, size_t k1, double* sy,
                   double* sxy) {
  double a[F], b[F];
  for (int f = 0; f < F; ++f) {
    a[f] = sy[f];
    b[f] = sxy[f];
  }
  for (size_t k = k0; k < k1; ++k) {
    for (int f = 0; f < F; ++f) {
      const double v = y[f][k] - ref_db;
      a[f] += v;
      b[f] += ((double)k - xc[f]) * v;
    }
  }
  for (int f = 0; f < F; ++f) {
    sy[f] = a[f];
    sxy[f] = b[f];
  }
}

}  // namespace

void fit_decay_ranges(const double* edc, const double* edc_db, size_t usable_end, double reference,
                      double sample_rate_hz, const std::vector<DecayRangeDb>& ranges, std::vector<DecayFit>* fits) {
  fits->assign(ranges.size(), DecayFit());
  // The ranges that can be fitted, shortest first: all run together up to the shortest's end, then
  // the longer ones on.
  std::vector<std::pair<size_t, FitRange>> todo;
  for (size_t r = 0; r < ranges.size(); ++r) {
    const FitRange fr = find_fit_range(edc, usable_end, reference, ranges[r].upper_db, ranges[r].lower_db);
    if (fr.ok) todo.push_back({r, fr});
  }
  std::sort(todo.begin(), todo.end(), [](const auto& p, const auto& q) {
    return p.second.last - p.second.first < q.second.last - q.second.first;
  });
  const double ref_db = 10.0 * std::log10(reference);
  for (size_t start = 0; start < todo.size(); start += 3) {
    const size_t count = std::min<size_t>(3, todo.size() - start);
    const double* y[3] = {nullptr, nullptr, nullptr};
    double xc[3] = {0, 0, 0}, sy[3] = {0, 0, 0}, sxy[3] = {0, 0, 0};
    size_t m[3] = {0, 0, 0};
    for (size_t f = 0; f < count; ++f) {
      const FitRange& fr = todo[start + f].second;
      m[f] = fr.last - fr.first + 1;
      y[f] = edc_db + fr.first;
      xc[f] = 0.5 * (double)(m[f] - 1);
    }
    // Lockstep over the terms all (then the longer two, then the longest) still have.
    if (count == 3) add_fit_terms<3>(y, ref_db, xc, 0, m[0], sy, sxy);
    if (count >= 2) add_fit_terms<2>(y + count - 2, ref_db, xc + count - 2, count == 3 ? m[0] : 0, m[count - 2],
                                     sy + count - 2, sxy + count - 2);
    add_fit_terms<1>(y + count - 1, ref_db, xc + count - 1, count >= 2 ? m[count - 2] : 0, m[count - 1],
                     sy + count - 1, sxy + count - 1);
    for (size_t f = 0; f < count; ++f) {
      const FitRange& fr = todo[start + f].second;
      (*fits)[todo[start + f].first] = fit_from_sums(sy[f], sxy[f], fr.first, m[f], sample_rate_hz);
    }
  }
}

DecayFit fit_decay_range(const double* edc, size_t usable_end, double reference, double sample_rate_hz,
                         double upper_db, double lower_db) {
  const FitRange r = find_fit_range(edc, usable_end, reference, upper_db, lower_db);
  if (!r.ok) return DecayFit();
  std::vector<double> db(r.last - r.first + 1);
  energy_to_db(edc + r.first, db.size(), db.data());
  return line_fit(db.data(), r.first, r.last, reference, sample_rate_hz);
}

DecayFit fit_decay_range(const double* edc, const double* edc_db, size_t usable_end, double reference,
                         double sample_rate_hz, double upper_db, double lower_db) {
  const FitRange r = find_fit_range(edc, usable_end, reference, upper_db, lower_db);
  if (!r.ok) return DecayFit();
  return line_fit(edc_db + r.first, r.first, r.last, reference, sample_rate_hz);
}

}  // namespace tsrir
