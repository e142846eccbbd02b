#include "sim/spectral_shaping.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "sim/octave_filters.h"
#include "util/error.h"

namespace tsrir::sim {

double interpolate_band_db(const BandValues& band_db, double f_hz) {
  double v = 0.0;
  for (int b = 0; b < kNumOctaveBands; ++b) v += band_db[b] * octave_crossover_gain(b, f_hz);
  return v;
}

std::vector<float> minimum_phase_fir(const std::vector<double>& magnitude_db, size_t fft_size, size_t num_taps) {
  if (magnitude_db.size() != fft_size / 2 + 1 || fft_size % 2 != 0 || num_taps > fft_size) {
    throw Error("minimum_phase_fir: inconsistent sizes");
  }
  // Real cepstrum of log|H| (natural log), folded onto the causal part, exponentiated.
  const size_t bins = fft_size / 2 + 1;
  RealFft fft(fft_size);
  std::vector<std::complex<float>> spec(bins);
  for (size_t k = 0; k < bins; ++k) spec[k] = static_cast<float>(magnitude_db[k] * std::log(10.0) / 20.0);
  std::vector<float> cep(fft_size);
  fft.inverse(spec.data(), cep.data());
  for (float& c : cep) c /= static_cast<float>(fft_size);
  std::vector<float> folded(fft_size, 0.0f);
  folded[0] = cep[0];
  for (size_t n = 1; n < fft_size / 2; ++n) folded[n] = 2.0f * cep[n];
  folded[fft_size / 2] = cep[fft_size / 2];
  fft.forward(folded.data(), spec.data());
  for (auto& s : spec) {
    const std::complex<double> z(s.real(), s.imag());
    const std::complex<double> e = std::exp(z) / static_cast<double>(fft_size);
    s = std::complex<float>(static_cast<float>(e.real()), static_cast<float>(e.imag()));
  }
  std::vector<float> h(fft_size);
  fft.inverse(spec.data(), h.data());
  h.resize(num_taps);
  const size_t fade = num_taps / 4;
  constexpr double kPi = 3.14159265358979323846;
  for (size_t i = 0; i < fade; ++i) {
    h[num_taps - fade + i] *= static_cast<float>(0.5 * (1.0 + std::cos(kPi * (i + 1) / (fade + 1))));
  }
  return h;
}

std::vector<float> zero_phase_filter(const std::vector<float>& x, double sample_rate_hz, size_t pad,
                                     double (*gain)(double f_hz, const void* arg), const void* arg) {
  const size_t n = x.size();
  const size_t size = next_fast_fft_size(n + pad);
  RealFft fft(size);
  std::vector<float> buffer(size, 0.0f);
  std::copy(x.begin(), x.end(), buffer.begin());
  std::vector<std::complex<float>> spec(fft.num_bins());
  fft.forward(buffer.data(), spec.data());
  for (size_t k = 0; k < spec.size(); ++k) {
    spec[k] *= static_cast<float>(gain(k * sample_rate_hz / size, arg) / size);
  }
  fft.inverse(spec.data(), buffer.data());
  buffer.resize(n);
  return buffer;
}

}  // namespace tsrir::sim
