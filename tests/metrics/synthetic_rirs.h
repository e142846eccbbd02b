// Synthetic RIRs with known answers, generated without any of the code under test (plain
// std::mt19937_64 noise and std::sin/std::exp in double precision).
#pragma once
#include <cstdint>
#include <vector>

#include "io/signal.h"

namespace tsrir_test {

struct ExponentialRirSpec {
  double sample_rate_hz = 16000;
  double duration_s = 1.0;
  size_t direct_sample = 160;    // where the direct impulse sits
  double direct_amplitude = 0;   // 0 = no direct impulse
  size_t tail_start_sample = 160;
  double tail_amplitude = 0.1;   // rms of the tail's noise at its start
  double t60_s = 0.5;            // energy decays 60 dB in t60
  double noise_rms = 0;          // stationary white noise floor over the whole file
  uint64_t seed = 1;
};

// Direct impulse + white Gaussian noise under an exponential envelope + optional noise floor.
// The noiseless part (for known DRR/C50) is returned through *clean when given.
tsrir::Signal exponential_rir(const ExponentialRirSpec& spec, std::vector<double>* clean = nullptr);

// A decay whose octave band b decays with t60_s[b]: one exponentially damped tone (amplitude 0.1,
// random phase) at each band centre, plus an optional white noise floor. A tone's energy decay is
// exactly exponential, unlike band noise, whose realised decay scatters around the envelope.
tsrir::Signal multiband_rir(double sample_rate_hz, double duration_s, const std::vector<double>& centers_hz,
                            const std::vector<double>& t60_s, size_t start_sample, double noise_rms, uint64_t seed);

// sum of x[i]^2 for i in [begin, end)
double energy(const std::vector<double>& x, size_t begin, size_t end);

}  // namespace tsrir_test
