#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "eq/relative_gain.h"
#include "util/error.h"
#include "util/rng.h"

using namespace tsrir;

namespace {

// A signal of exactly n = 16384 samples whose DFT magnitude is `level_db(f)` at every bin, with
// random phases: the gains the EQ reads off it are known exactly (its analysis grid is the
// same 16384 points).
template <typename LevelFn>
Signal signal_with_spectrum(double fs, LevelFn level_db, uint64_t seed) {
  const size_t n = 16384;
  Rng rng(seed);
  std::vector<std::complex<float>> spec(n / 2 + 1);
  for (size_t b = 0; b <= n / 2; ++b) {
    const double mag = std::pow(10.0, level_db(b * fs / n) / 20.0);
    const double phase = (b == 0 || b == n / 2) ? 0.0 : rng.uniform(0, 2 * M_PI);
    spec[b] = std::polar(static_cast<float>(mag), static_cast<float>(phase));
  }
  Signal s;
  s.id = "constructed";
  s.sample_rate_hz = fs;
  s.samples.resize(n);
  RealFft(n).inverse(spec.data(), s.samples.data());
  for (float& v : s.samples) v /= static_cast<float>(n);
  return s;
}

// Per-octave levels (test's own band edges: centre / sqrt2 .. centre * sqrt2).
const double kLevels[8] = {7.0, -3.0, 4.0, 1.5, 2.0, -2.5, -6.0, -11.0};
double octave_level_db(double f) {
  for (int j = 0; j < 8; ++j) {
    const double c = 62.5 * std::pow(2.0, j);
    if (f >= c / std::sqrt(2.0) && f < c * std::sqrt(2.0)) return kLevels[j];
  }
  return f < 50 ? 0.0 : 20.0;  // outside the bands: must not leak in (20 dB above 11.3 kHz)
}

}  // namespace

TEST(RelativeGains, OctaveBandPowerOfAKnownSpectrum) {
  const Signal s = signal_with_spectrum(16000, octave_level_db, 1);
  const RelativeGainsDb g = relative_gains_db(s, GainMethod::kOctave);
  for (int k = 0; k < kEqNumPoints; ++k) {
    const int node = eq_node_of_point(k);
    EXPECT_NEAR(g[k], kLevels[node] - kLevels[kEqReferenceNode], 0.01) << kEqPointsHz[k];
  }
}

TEST(RelativeGains, EightKilohertzBandIsClippedAtNyquistOnlyAt16k) {
  // At 48 kHz the 8 kHz octave is [5657, 11314] Hz; the +20 dB above 11314 Hz must not count.
  const Signal s48 = signal_with_spectrum(48000, octave_level_db, 2);
  EXPECT_NEAR(relative_gains_db(s48, GainMethod::kOctave)[6], kLevels[7] - kLevels[4], 0.01);
  // At 16 kHz the band is [5657, 8000]: a level that differs above 8 kHz cannot exist, and a step
  // inside the clipped band is averaged over 5657..8000 only.
  auto stepped = [](double f) { return f >= 5657 ? (f >= 7000 ? 3.0 : -3.0) : 0.0; };
  const Signal s16 = signal_with_spectrum(16000, stepped, 3);
  const double expected = 10 * std::log10(((7000 - 5657) * std::pow(10, -0.3) + (8000 - 7000) * std::pow(10, 0.3)) / (8000 - 5657));
  EXPECT_NEAR(relative_gains_db(s16, GainMethod::kOctave)[6], expected, 0.02);
  EqBandGrid grid(16384, 16000, GainMethod::kOctave);
  EXPECT_EQ(grid.last_bin(7), 8192u);                      // Nyquist bin
  EXPECT_NEAR(grid.bin_hz(grid.first_bin(7)), 5657, 1.0);  // 8000 / sqrt 2
}

TEST(RelativeGains, BinAndSmoothMethods) {
  // Levels that vary inside a band: 1/3 octave and single-bin readings see the local level.
  auto sloped = [](double f) { return f < 20 ? 0.0 : 6.0 * std::log2(f / 1000.0); };  // +6 dB / octave
  const Signal s = signal_with_spectrum(16000, sloped, 4);
  for (GainMethod m : {GainMethod::kBin, GainMethod::kSmooth}) {
    const RelativeGainsDb g = relative_gains_db(s, m);
    for (int k = 0; k < kEqNumPoints; ++k) {
      // bin: exact up to the bin's offset from the point (< 0.5 bin = 0.49 Hz, < 0.07 dB at
      // 62.5 Hz); smooth: power mean of a tilted third octave is within 0.1 dB of its centre.
      double expected = sloped(kEqPointsHz[k]);
      if (m == GainMethod::kSmooth && k == kEqNumPoints - 1) {
        // At 16 kHz the 8 kHz third octave is clipped to [7127, 8000] Hz: the power mean of the
        // sloped level over that half band, integrated here in 1 Hz steps.
        double sum = 0, count = 0;
        for (double f = 8000 / std::pow(2.0, 1.0 / 6); f <= 8000; f += 1.0, ++count) sum += std::pow(10.0, sloped(f) / 10);
        expected = 10 * std::log10(sum / count);
      }
      EXPECT_NEAR(g[k], expected, 0.1) << gain_method_name(m) << " " << kEqPointsHz[k];
    }
  }
}

TEST(RelativeGains, ClearErrors) {
  Signal silent;
  silent.id = "quiet";
  silent.sample_rate_hz = 16000;
  silent.samples.assign(16000, 0.0f);
  try {
    relative_gains_db(silent, GainMethod::kOctave);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'quiet'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("silent"), std::string::npos);
  }
  Signal low = signal_with_spectrum(16000, octave_level_db, 5);
  low.sample_rate_hz = 8000;
  EXPECT_THROW(relative_gains_db(low, GainMethod::kOctave), Error);
  // No energy in the 62.5 Hz band at all: a 4 kHz tone of exactly 4096 periods in 16384 samples.
  Signal no_lf;
  no_lf.id = "tone";
  no_lf.sample_rate_hz = 16000;
  for (int n = 0; n < 16384; ++n) no_lf.samples.push_back(n % 4 == 0 ? 1.0f : n % 4 == 2 ? -1.0f : 0.0f);
  try {
    relative_gains_db(no_lf, GainMethod::kOctave);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("62.5 Hz"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_gain_method("third"), Error);
}
