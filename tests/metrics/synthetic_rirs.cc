#include "synthetic_rirs.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace tsrir_test {

tsrir::Signal exponential_rir(const ExponentialRirSpec& spec, std::vector<double>* clean) {
  const size_t n = (size_t)std::llround(spec.duration_s * spec.sample_rate_hz);
  std::mt19937_64 gen(spec.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> c(n, 0.0);
  if (spec.direct_amplitude != 0 && spec.direct_sample < n) c[spec.direct_sample] = spec.direct_amplitude;
  // Amplitude envelope 10^(-3 t / T60): energy falls 60 dB in T60.
  for (size_t i = spec.tail_start_sample; i < n; ++i) {
    const double t = (double)(i - spec.tail_start_sample) / spec.sample_rate_hz;
    c[i] += spec.tail_amplitude * std::pow(10.0, -3.0 * t / spec.t60_s) * normal(gen);
  }
  tsrir::Signal s;
  s.id = "synthetic";
  s.sample_rate_hz = spec.sample_rate_hz;
  s.samples.resize(n);
  std::mt19937_64 noise_gen(spec.seed ^ 0x9e3779b97f4a7c15ull);
  for (size_t i = 0; i < n; ++i) {
    s.samples[i] = (float)(c[i] + (spec.noise_rms > 0 ? spec.noise_rms * normal(noise_gen) : 0.0));
  }
  if (clean) {
    // The float samples minus the noise are what the metric sees; keep the clean part in the
    // same precision so the expected values are those of the actual samples.
    clean->assign(n, 0.0);
    for (size_t i = 0; i < n; ++i) (*clean)[i] = (double)(float)c[i];
  }
  return s;
}

tsrir::Signal multiband_rir(double fs, double duration_s, const std::vector<double>& centers_hz,
                            const std::vector<double>& t60_s, size_t start_sample, double noise_rms, uint64_t seed) {
  const size_t n = (size_t)std::llround(duration_s * fs);
  std::vector<double> x(n, 0.0);
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (size_t b = 0; b < centers_hz.size(); ++b) {
    // Amplitude 10^(-3 t / T60): the tone's energy falls 60 dB in T60, exactly.
    const double phase = 2 * M_PI * uni(gen);
    const double w = 2 * M_PI * centers_hz[b] / fs;
    for (size_t i = start_sample; i < n; ++i) {
      const double t = (double)(i - start_sample) / fs;
      x[i] += 0.1 * std::pow(10.0, -3.0 * t / t60_s[b]) * std::sin(w * (double)(i - start_sample) + phase);
    }
  }
  std::normal_distribution<double> normal(0.0, 1.0);
  tsrir::Signal s;
  s.id = "multiband";
  s.sample_rate_hz = fs;
  s.samples.resize(n);
  for (size_t i = 0; i < n; ++i) s.samples[i] = (float)(x[i] + (noise_rms > 0 ? noise_rms * normal(gen) : 0.0));
  return s;
}

double energy(const std::vector<double>& x, size_t begin, size_t end) {
  double s = 0;
  for (size_t i = begin; i < end && i < x.size(); ++i) s += x[i] * x[i];
  return s;
}

}  // namespace tsrir_test
