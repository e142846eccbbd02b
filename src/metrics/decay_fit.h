// Energy decay curves and straight-line fits to them (the ISO 3382 way): backward integration of
// squared samples, evaluation ranges found on the monotone curve, least squares in dB over time.
#pragma once
#include <cstddef>
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

// 10*log10(x) for x > 0 in a form the compiler vectorises; absolute error below 1e-9 dB.
void energy_to_db(const double* x, size_t n, double* db);

}  // namespace tsrir
