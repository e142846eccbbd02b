// Lundeby et al. (Acustica 81, 1995) noise-floor detection, as ISO 3382-1 recommends and pyrato
// implements (docs/reference/spec-digest.md §1.4): the time where the decay meets the noise, the noise power and
// the late decay rate, from iterated regressions on a block-smoothed energy envelope.
#pragma once
#include <cstddef>
#include <string>

namespace tsrir {

struct LundebyResult {
  bool ok = false;
  std::string failure;            // why, when !ok
  size_t intersection = 0;        // first sample not used by the EDC (<= n)
  double noise_power = 0.0;       // mean squared amplitude of the noise floor
  double late_decay_time_s = 0.0; // -60 / late slope
  double peak_to_noise_db = 0.0;  // smoothed peak level over noise level
  int iterations = 0;
};

// energy: squared (band-filtered) samples starting at the onset. center_hz = 0 for broadband
// (30 ms initial blocks), else (800 / fc + 10) ms. A tail that is exactly zero counts as no noise:
// intersection = n, noise_power = 0.
LundebyResult lundeby_intersection(const double* energy, size_t n, double sample_rate_hz, double center_hz);

// The same from the backward sums tail[i] = sum_{k>=i} energy[k], i in [0, n] (tail[n] = 0), which
// the caller usually needs for its decay curve anyway.
LundebyResult lundeby_intersection_from_tail(const double* tail, size_t n, double sample_rate_hz, double center_hz);

// Energy (sum of squared samples) of the exponential tail cut off at the intersection:
// noise_power * T_late / (6 ln 10) * fs. It is added to the truncated EDC.
double lundeby_tail_energy(const LundebyResult& result, double sample_rate_hz);

}  // namespace tsrir
