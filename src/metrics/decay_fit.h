// Energy decay curves and straight-line fits to them (the ISO 3382 way): backward integration of
// squared samples, evaluation ranges found on the monotone curve, least squares in dB over time.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tsrir {

// E[n] = tail_energy + sum_{k=n}^{N-1} energy[k] (double accumulation); E has N entries.
std::vector<double> backward_integral(const double* energy, size_t n, double tail_energy = 0.0);

// Smallest index i in [0, n) with edc[i] <= level (edc non-increasing, binary search); n if none.
size_t first_index_at_or_below(const double* edc, size_t n, double level);

struct DecayFit {
  bool ok = false;
  size_t first = 0, last = 0;      // fitted samples [first, last]
  double slope_db_per_s = 0.0;
  double intercept_db = 0.0;       // line value at sample 0, dB re reference
  double decay_time_s() const;     // -60 / slope (NaN unless ok and slope < 0)
};

// Fits 10*log10(edc[i] / reference) against i / fs over the samples from the first one at or
// below upper_db to the last one above lower_db (upper_db > lower_db, both <= 0). Not ok when
// lower_db is not reached within [0, usable_end) or fewer than 3 samples lie in the range.
DecayFit fit_decay_range(const double* edc, size_t usable_end, double reference, double sample_rate_hz,
                         double upper_db, double lower_db);

// As above with edc_db[i] = 10*log10(edc[i]) precomputed for every index the fit can touch
// (those up to the first sample at or below lower_db), so several ranges share one conversion.
DecayFit fit_decay_range(const double* edc, const double* edc_db, size_t usable_end, double reference,
                         double sample_rate_hz, double upper_db, double lower_db);

// Several ranges of one curve at once, fits[r] = fit_decay_range(edc, edc_db, ..., ranges[r]) to the
// bit: each range's sums are added in their own order, the ranges' additions interleaved (one
// range's sums are chains of dependent additions; side by side, the chains overlap).
struct DecayRangeDb {
  double upper_db = 0.0, lower_db = 0.0;
};
void fit_decay_ranges(const double* edc, const double* edc_db, size_t usable_end, double reference,
                      double sample_rate_hz, const std::vector<DecayRangeDb>& ranges, std::vector<DecayFit>* fits);

// 10*log10(x) for x > 0 in a form the compiler vectorises; absolute error below 1e-9 dB. Each value
// is normal_energy_to_db's, to the bit, whichever CPU clone runs (decay_fit.cc).
void energy_to_db(const double* x, size_t n, double* db);

// energy_to_db's arithmetic for one normal, finite x > 0: log via an exponent/mantissa split with
// the mantissa in [sqrt(1/2), sqrt(2)) and the atanh series of the mantissa. Integer steps only
// (64-bit add/shift/and, the 2^52 magic number for the exponent), no branches, so a loop of it
// vectorises. Zeros, subnormals, infinities and NaN give garbage here (energy_to_db patches them).
inline double normal_energy_to_db(double x) {
  constexpr double kDbPerLn = 10.0 / 2.302585092994045684;
  constexpr double kLn2 = 0.693147180559945309;
  constexpr uint64_t kSqrtHalfBits = 0x3FE6A09E667F3BCDull;
  constexpr uint64_t kMantissa = 0x000FFFFFFFFFFFFFull;
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
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
  return kDbPerLn * (e * kLn2 + 2.0 * r * series);
}

}  // namespace tsrir
