#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "dsp/bands.h"
#include "dsp/convolve.h"
#include "dsp/fft.h"
#include "util/rng.h"

using namespace tsrir;

namespace {
std::vector<float> noise(size_t n, uint64_t seed) {
  Rng r(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = static_cast<float>(r.normal());
  return v;
}
std::vector<double> to_double(const std::vector<float>& v) { return {v.begin(), v.end()}; }
}  // namespace

// Float FFT convolution vs float64 direct convolution. Error bound: float eps (6e-8) times
// log2(FFT size) times sqrt(M) times the signal scale; 1e-4 of the output RMS covers every size here
// with a margin of >10x while catching any indexing or scaling bug (those give O(1) errors).
TEST(Convolve, MatchesDirectFloat64ReferenceAcrossSizes) {
  const std::vector<std::pair<size_t, size_t>> sizes = {{1, 1},      {10, 3},     {100, 100},  {1000, 65},
                                                        {5000, 300}, {16000, 4000}, {40000, 16000}, {300, 5000}};
  for (auto [n, m] : sizes) {
    auto x = noise(n, n), h = noise(m, m + 1);
    auto y = fft_convolve(x, h);
    auto ref = direct_convolve(to_double(x), to_double(h));
    ASSERT_EQ(y.size(), n + m - 1);
    double rms = 0;
    for (double v : ref) rms += v * v;
    rms = std::sqrt(rms / ref.size());
    double max_err = 0;
    for (size_t i = 0; i < y.size(); ++i) max_err = std::max(max_err, std::fabs(y[i] - ref[i]));
    EXPECT_LT(max_err, 1e-4 * rms) << "n=" << n << " m=" << m;
  }
}

TEST(Convolve, ConvolverReusableAndOverlapSaveMatchesSingleShot) {
  auto h = noise(2000, 3);
  Convolver c(h);
  for (size_t n : {10u, 7000u, 50000u}) {
    auto x = noise(n, n);
    auto y = c.convolve(x);
    auto ref = direct_convolve(to_double(x), to_double(h));
    double max_err = 0, peak = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      max_err = std::max(max_err, std::fabs(y[i] - ref[i]));
      peak = std::max(peak, std::fabs(ref[i]));
    }
    EXPECT_LT(max_err, 1e-5 * peak * 10) << n;
  }
}

TEST(Convolve, ImpulseIsIdentityAndDelay) {
  std::vector<float> h(200, 0.0f);
  h[17] = 1.0f;
  auto x = noise(3000, 9);
  auto y = fft_convolve(x, h);
  for (size_t i = 0; i < x.size(); ++i) ASSERT_NEAR(y[i + 17], x[i], 1e-5);
}

TEST(Fft, ParsevalAndFastSizes) {
  auto x = noise(1000, 5);
  const size_t n = 1024;
  auto p = power_spectrum(x, n);
  double time_energy = 0, freq_energy = 0;
  for (float v : x) time_energy += v * v;
  for (size_t k = 0; k < p.size(); ++k) freq_energy += (k == 0 || k == n / 2 ? 1.0 : 2.0) * p[k];
  EXPECT_NEAR(freq_energy / n, time_energy, 1e-4 * time_energy);
  EXPECT_EQ(next_fast_fft_size(1025), 1080u);
  EXPECT_EQ(next_fast_fft_size(7), 8u);
  // Never a size with fewer than three factors of 2 (odd 16875, 2 x 9375 = 18750: 2-4x slower).
  EXPECT_EQ(next_fast_fft_size(16801), 17280u);
  EXPECT_EQ(next_fast_fft_size(18433), 19200u);
  for (size_t n = 2; n < 5000; n += 7) EXPECT_EQ(next_fast_fft_size(n) % 8, 0u) << n;
}

TEST(Bands, CentresAndLabels) {
  EXPECT_EQ(octave_band_label(62.5), "62.5");
  EXPECT_EQ(octave_band_label(1000), "1000");
  EXPECT_EQ(octave_band_index(4000), 6);
  EXPECT_EQ(octave_band_index(3000), -1);
  EXPECT_NEAR(octave_upper_edge_hz(8000), 11313.7, 0.1);
}
