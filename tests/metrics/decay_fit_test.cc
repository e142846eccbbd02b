// Schroeder integration, ISO range fits, the fast dB conversion and Lundeby's noise detection.
#include "metrics/decay_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "metrics/lundeby.h"
#include "metrics/rir_metrics.h"

namespace tsrir {
namespace {

TEST(DecayFit, BackwardIntegralAddsTail) {
  const double e[] = {1, 2, 3, 4};
  const std::vector<double> edc = backward_integral(e, 4, 0.5);
  ASSERT_EQ(edc.size(), 4u);
  EXPECT_DOUBLE_EQ(edc[0], 10.5);
  EXPECT_DOUBLE_EQ(edc[1], 9.5);
  EXPECT_DOUBLE_EQ(edc[3], 4.5);
}

TEST(DecayFit, SchroederDecayDbIsRelativeToStart) {
  std::vector<float> h = {0.0f, 1.0f, 0.5f, 0.5f, 0.0f};
  const std::vector<double> edc = schroeder_decay_db(h, 1);
  ASSERT_EQ(edc.size(), 4u);
  EXPECT_DOUBLE_EQ(edc[0], 0.0);
  EXPECT_NEAR(edc[1], 10 * std::log10(0.5 / 1.5), 1e-12);
  EXPECT_NEAR(edc[2], 10 * std::log10(0.25 / 1.5), 1e-12);
  EXPECT_TRUE(std::isinf(edc[3]) && edc[3] < 0);
}

TEST(DecayFit, FirstIndexAtOrBelowOnMonotoneCurve) {
  const double edc[] = {10, 8, 8, 5, 1};
  EXPECT_EQ(first_index_at_or_below(edc, 5, 8), 1u);
  EXPECT_EQ(first_index_at_or_below(edc, 5, 7.9), 3u);
  EXPECT_EQ(first_index_at_or_below(edc, 5, 0.5), 5u);
  EXPECT_EQ(first_index_at_or_below(edc, 5, 100), 0u);
}

TEST(DecayFit, EnergyToDbMatchesLog10) {
  std::vector<double> x;
  for (double v = 1e-300; v < 1e300; v *= 1.37) x.push_back(v);
  x.push_back(1.0);
  x.push_back(0.0);
  x.push_back(4.9e-324);  // subnormal
  std::vector<double> db(x.size());
  energy_to_db(x.data(), x.size(), db.data());
  for (size_t i = 0; i < x.size(); ++i) {
    const double want = 10 * std::log10(x[i]);
    if (std::isinf(want)) {
      EXPECT_TRUE(std::isinf(db[i]));
    } else {
      ASSERT_NEAR(db[i], want, 1e-9) << x[i];
    }
  }
}

// Whichever clone this CPU runs (AVX-512F, AVX2 or baseline), the same bits as the scalar steps
// compiled here for baseline x86-64 (no FMA, each step rounded on its own): the metrics' results
// do not depend on the machine.
TEST(DecayFit, EnergyToDbIsTheScalarArithmeticToTheBit) {
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> exponent(-200.0, 20.0);
  std::vector<double> x(4099);
  for (double& v : x) v = std::pow(10.0, exponent(gen));
  std::vector<double> db(x.size());
  energy_to_db(x.data(), x.size(), db.data());
  for (size_t i = 0; i < x.size(); ++i) ASSERT_EQ(db[i], normal_energy_to_db(x[i])) << i << " " << x[i];
}

TEST(DecayFit, RecoversExactExponentialDecay) {
  const double fs = 16000, t60 = 0.73;
  std::vector<double> edc(16000);
  for (size_t i = 0; i < edc.size(); ++i) edc[i] = std::pow(10.0, -6.0 * (i / fs) / t60);
  const DecayFit t30 = fit_decay_range(edc.data(), edc.size(), edc[0], fs, -5, -35);
  ASSERT_TRUE(t30.ok);
  EXPECT_NEAR(t30.decay_time_s(), t60, 1e-9);
  EXPECT_NEAR(t30.intercept_db, 0.0, 1e-9);
  // The fitted samples span -5 .. -35 dB.
  EXPECT_NEAR(-60.0 * (t30.first / fs) / t60, -5.0, 0.01);
  EXPECT_NEAR(-60.0 * (t30.last / fs) / t60, -35.0, 0.01);
}

TEST(DecayFit, RangeMustBeReachedInsideUsablePart) {
  const double fs = 16000, t60 = 1.0;
  std::vector<double> edc(16000);
  for (size_t i = 0; i < edc.size(); ++i) edc[i] = std::pow(10.0, -6.0 * (i / fs) / t60);
  // -35 dB is reached at 0.583 s; usable part ends at 0.5 s.
  EXPECT_FALSE(fit_decay_range(edc.data(), 8000, edc[0], fs, -5, -35).ok);
  EXPECT_TRUE(fit_decay_range(edc.data(), 8000, edc[0], fs, -5, -25).ok);
  EXPECT_TRUE(std::isnan(DecayFit().decay_time_s()));
}

// Energy of an exponential decay (T60) from level 1 plus white noise of power noise_power.
std::vector<double> noisy_decay_energy(double fs, double seconds, double t60, double noise_power, uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> normal;
  std::vector<double> e((size_t)(fs * seconds));
  for (size_t i = 0; i < e.size(); ++i) {
    const double a = std::pow(10.0, -3.0 * (i / fs) / t60) * normal(gen);
    const double v = a + std::sqrt(noise_power) * normal(gen);
    e[i] = v * v;
  }
  return e;
}

TEST(Lundeby, FindsWhereTheDecayMeetsTheNoise) {
  const double fs = 16000, t60 = 0.5;
  for (double noise_db : {-40.0, -50.0, -60.0}) {
    const double noise = std::pow(10.0, noise_db / 10.0);
    const std::vector<double> e = noisy_decay_energy(fs, 1.5, t60, noise, 7);
    const LundebyResult r = lundeby_intersection(e.data(), e.size(), fs, 0.0);
    ASSERT_TRUE(r.ok) << r.failure;
    // The decay 10^(-6 t / T) meets the noise at t = -noise_db / 60 * T.
    const double expected_s = -noise_db / 60.0 * t60;
    // Lundeby's estimate scatters by a few blocks (block = 1/5 of a 10 dB decay = 17 ms here).
    EXPECT_NEAR(r.intersection / fs, expected_s, 0.04) << noise_db;
    EXPECT_NEAR(10 * std::log10(r.noise_power), noise_db, 0.5) << noise_db;
    EXPECT_NEAR(r.late_decay_time_s, t60, 0.1 * t60) << noise_db;
  }
}

TEST(Lundeby, CompensationRestoresTheTruncatedTail) {
  const double fs = 16000, t60 = 0.5, noise_db = -50;
  const std::vector<double> e = noisy_decay_energy(fs, 1.5, t60, std::pow(10.0, noise_db / 10.0), 11);
  const LundebyResult r = lundeby_intersection(e.data(), e.size(), fs, 0.0);
  ASSERT_TRUE(r.ok);
  // Energy of the noiseless decay beyond the intersection, analytically.
  const double tail = fs * t60 / (6 * std::log(10.0)) * std::pow(10.0, -6.0 * (r.intersection / fs) / t60);
  // The tail model uses the noise level at the intersection: within a factor 1.6 (2 dB) is all
  // the noise-level/time scatter allows, and it is ~1e-5 of the total energy.
  const double got = lundeby_tail_energy(r, fs);
  EXPECT_NEAR(10 * std::log10(got / tail), 0.0, 2.0);
}

TEST(Lundeby, FailsWithoutDecay) {
  std::mt19937_64 gen(1);
  std::normal_distribution<double> normal;
  std::vector<double> e(16000);
  for (double& v : e) {
    const double a = normal(gen);
    v = a * a;
  }
  EXPECT_FALSE(lundeby_intersection(e.data(), e.size(), 16000, 1000).ok);
}

TEST(Lundeby, SilentTailMeansNoNoise) {
  std::vector<double> e(16000, 0.0);
  for (size_t i = 0; i < 4000; ++i) e[i] = std::pow(10.0, -6.0 * (i / 16000.0) / 0.3);
  const LundebyResult r = lundeby_intersection(e.data(), e.size(), 16000, 0.0);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.intersection, e.size());
  EXPECT_EQ(lundeby_tail_energy(r, 16000), 0.0);
}

}  // namespace
}  // namespace tsrir
