// rir-perturb's controls measured by rir-metrics on RIRs whose truth is known by construction and
// that are made another way than the perturbation works: a direct impulse plus Gaussian noise
// under an exponential energy envelope of a chosen T60 (the same in every band), optionally above a
// constant noise floor, as a measurement has it. The checks are on what a user relies on: the T60,
// DRR and low-band energy that rir-metrics then reports, and what must stay as measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "dsp/fft.h"
#include "metrics/rir_metrics.h"
#include "perturb/rir_perturb.h"
#include "util/error.h"

namespace tsrir {
namespace {

constexpr double kFs = 16000.0;

// Direct impulse at 10 ms (amplitude 1), then noise whose energy decays by 60 dB per t60_s, at
// `diffuse_db` below the direct sound's energy density at its start; optional floor (dB re 1).
Signal synthetic_rir(double t60_s, unsigned seed, double floor_db = -300.0, double diffuse_db = -12.0,
                     double length_s = 1.0) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  Signal s;
  s.id = "syn" + std::to_string(seed);
  s.sample_rate_hz = kFs;
  s.samples.assign(size_t(length_s * kFs), 0.0f);
  const size_t direct = size_t(0.010 * kFs);
  s.samples[direct] = 1.0f;
  const double start_amp = std::pow(10.0, diffuse_db / 20.0);
  const double floor_amp = std::pow(10.0, floor_db / 20.0);
  for (size_t i = direct + 16; i < s.size(); ++i) {
    const double t = double(i - direct) / kFs;
    s.samples[i] = float(start_amp * normal(gen) * std::pow(10.0, -3.0 * t / t60_s));
  }
  for (size_t i = 0; i < s.size(); ++i) s.samples[i] += float(floor_amp * normal(gen));
  return s;
}

double band_energy_db(const std::vector<float>& x, double lo_hz, double hi_hz) {
  const size_t n = next_fast_fft_size(x.size());
  const std::vector<double> p = power_spectrum(x, n);
  double e = 0;
  for (size_t k = 1; k < p.size(); ++k) {
    const double f = k * kFs / double(n);
    if (f >= lo_hz && f < hi_hz) e += p[k];
  }
  return 10 * std::log10(e);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Tolerances from 100 draws the tests do not use (seeds 100-199): one draw's measured ratio
// scatters by about +-10 % around the asked scale (the ISO T30 fit on one noise realisation),
// the median of 8 draws by about 2 %, hence +-6 %. Stretching (x2) measures ~4 % short in the
// median: the noise floor is faded out at the Lundeby point, so the stretched decay has less range
// for the T30 fit (rir_perturb.h says so); its lower bound is -10 %.
class T60Scale : public ::testing::TestWithParam<double> {};

TEST_P(T60Scale, MeasuredT60ScalesAndTheDirectSoundStays) {
  const double scale = GetParam();
  std::vector<double> ratios;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    // A measured-like RIR: its decay meets a noise floor 73 dB below its start (the case where a
    // stretched envelope would amplify the noise if it were not faded out first).
    const Signal in = synthetic_rir(0.5, seed, -85.0);
    RirPerturbation p;
    p.t60_scale = scale;
    PerturbationRecord record;
    const Signal out = perturb_rir(in, p, 0, &record);
    ASSERT_EQ(out.size(), in.size());
    const RirMetrics before = measure_rir(in), after = measure_rir(out);
    ASSERT_TRUE(std::isfinite(before.t60_s) && std::isfinite(after.t60_s));
    ratios.push_back(after.t60_s / before.t60_s / scale);
    for (size_t i = 0; i <= size_t(0.010 * kFs) + 40; ++i) ASSERT_EQ(out.samples[i], in.samples[i]) << i;
    if (scale > 1) {
      EXPECT_GT(record.noise_cut_sample, 0u) << "the floor must be faded out before the envelope grows";
      EXPECT_EQ(out.samples.back(), 0.0f);
    }
  }
  EXPECT_GT(median(ratios), scale > 1 ? 0.90 : 0.94);
  EXPECT_LT(median(ratios), 1.06);
}
INSTANTIATE_TEST_SUITE_P(Controls, T60Scale, ::testing::Values(0.33, 0.5, 2.0));

// The direct sound well above the diffuse field (-20 dB), so that it stays the largest sample
// after -6 dB, as rir-metrics' DRR window needs. Over 100 unused draws the change fell within
// -0.33 .. +0.94 dB of the offset (median +0.25 for -6 dB: the ramps inside the window leave a
// little diffuse energy unscaled); the median of 8 must lie within 0.4 dB.
TEST(DrrOffset, MovesTheMeasuredDrrAndLeavesTheDecay) {
  for (double offset : {-6.0, 6.0}) {
    std::vector<double> changes;
    for (unsigned seed = 1; seed <= 8; ++seed) {
      const Signal in = synthetic_rir(0.6, seed, -300.0, -20.0);
      RirPerturbation p;
      p.drr_offset_db = offset;
      const Signal out = perturb_rir(in, p, 0, nullptr);
      const RirMetrics before = measure_rir(in), after = measure_rir(out);
      changes.push_back(after.drr_db - before.drr_db);
      // The decay is not touched; the T30 fit moves a little because the EDC's start (-5 dB) shifts
      // with the direct sound's share of the energy: at most 2.5 % over the 100 unused draws.
      EXPECT_NEAR(after.t60_s, before.t60_s, 0.04 * before.t60_s) << offset;
    }
    EXPECT_NEAR(median(changes), offset, 0.4) << offset;
  }
}

TEST(LfRinging, AddsTheAskedEnergyBelowItsBandOnly) {
  const Signal in = synthetic_rir(0.6, 9);
  RirPerturbation p;
  p.lf_ringing_db = 10.0;
  const Signal out = perturb_rir(in, p, 5, nullptr);
  // The ringing's energy is 10 dB above the RIR's own below 200 Hz, so that band grows by
  // 10 log10(1 + 10) = 10.4 dB, give or take the cross term of two independent signals.
  EXPECT_NEAR(band_energy_db(out.samples, 0, 200) - band_energy_db(in.samples, 0, 200), 10.41, 0.6);
  EXPECT_NEAR(band_energy_db(out.samples, 1000, 8000), band_energy_db(in.samples, 1000, 8000), 0.05);
  // Reproducible from (seed, id); another id draws other modes.
  EXPECT_EQ(perturb_rir(in, p, 5, nullptr).samples, out.samples);
  Signal other = in;
  other.id = "another";
  EXPECT_NE(perturb_rir(other, p, 5, nullptr).samples, out.samples);
}

TEST(Perturb, NothingAskedIsTheInput) {
  const Signal in = synthetic_rir(0.6, 4);
  EXPECT_EQ(perturb_rir(in, RirPerturbation(), 0, nullptr).samples, in.samples);
}

TEST(Perturb, AnRirWithoutMeasurableDecayIsAnErrorNamingIt) {
  Signal s;
  s.id = "click";
  s.sample_rate_hz = kFs;
  s.samples.assign(8000, 0.0f);   // digital silence: nothing to measure a decay on
  RirPerturbation p;
  p.t60_scale = 0.5;
  try {
    perturb_rir(s, p, 0, nullptr);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("click"), std::string::npos) << e.what();
  }
}

TEST(Perturb, OptionsAreValidated) {
  RirPerturbation p;
  p.t60_scale = 0;
  EXPECT_THROW(p.validate(), Error);
  p = RirPerturbation();
  p.lf_min_hz = 300;
  EXPECT_THROW(p.validate(), Error);
  p = RirPerturbation();
  p.drr_offset_db = 60;
  EXPECT_THROW(p.validate(), Error);
}

}  // namespace
}  // namespace tsrir
