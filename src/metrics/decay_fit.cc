#include "metrics/decay_fit.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

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

void energy_to_db(const double* x, size_t n, double* db) {
  // log via an exponent/mantissa split with the mantissa in [sqrt(1/2), sqrt(2)) and the atanh
  // series of the mantissa. Integer steps only (64-bit add/shift/and, the 2^52 magic number for
  // the exponent), no branches: the loop vectorises.
  constexpr double kDbPerLn = 10.0 / 2.302585092994045684;
  constexpr double kLn2 = 0.693147180559945309;
  constexpr uint64_t kSqrtHalfBits = 0x3FE6A09E667F3BCDull;
  constexpr uint64_t kMantissa = 0x000FFFFFFFFFFFFFull;
  for (size_t i = 0; i < n; ++i) {
    uint64_t bits;
    std::memcpy(&bits, &x[i], sizeof bits);
    // t >> 52 = k + 1024 where x = m 2^k, m in [sqrt(1/2), sqrt(2)).
    const uint64_t t = bits - kSqrtHalfBits + (1024ull << 52);
    const uint64_t exp_bits = 0x4330000000000000ull | (t >> 52);
    const uint64_t mant_bits = (t & kMantissa) + kSqrtHalfBits;
    double e, m;
    std::memcpy(&e, &exp_bits, sizeof e);
    std::memcpy(&m, &mant_bits, sizeof m);
    e -= 4503599627370496.0 + 1024.0;
    const double r = (m - 1.0) / (m + 1.0);
    const double r2 = r * r;
    const double series =
        1.0 + r2 * (1.0 / 3 + r2 * (1.0 / 5 + r2 * (1.0 / 7 + r2 * (1.0 / 9 + r2 * (1.0 / 11 + r2 * (1.0 / 13 + r2 / 15))))));
    db[i] = kDbPerLn * (e * kLn2 + 2.0 * r * series);
  }
  // Zeros, subnormals, infinities and NaN are rare: patch them with the library call.
  for (size_t i = 0; i < n; ++i) {
    if (!(x[i] >= std::numeric_limits<double>::min() && x[i] <= std::numeric_limits<double>::max())) {
      db[i] = 10.0 * std::log10(x[i]);
    }
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

// Least squares of db[i] - ref_db against i / fs for i in [first, last]; db indexed from first.
DecayFit line_fit(const double* db, size_t first, size_t last, double reference, double fs) {
  DecayFit fit;
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
  const double sxx = (double)m * ((double)m * m - 1.0) / 12.0;
  const double slope_per_sample = sxy / sxx;
  const double mean_y = sy / (double)m;
  fit.ok = true;
  fit.first = first;
  fit.last = last;
  fit.slope_db_per_s = slope_per_sample * fs;
  fit.intercept_db = mean_y - slope_per_sample * ((double)first + xc);
  return fit;
}

}  // namespace

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
