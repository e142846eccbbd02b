#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "eq/equalize.h"
#include "eq_test_util.h"
#include "util/error.h"

using namespace tsrir;

namespace {

size_t peak_index(const std::vector<float>& x) {
  return std::max_element(x.begin(), x.end(), [](float a, float b) { return std::abs(a) < std::abs(b); }) - x.begin();
}
double energy(const std::vector<float>& x) {
  double e = 0;
  for (float v : x) e += static_cast<double>(v) * v;
  return e;
}

const RelativeGainsDb kTarget = {6.0, 3.0, 0.5, -1.0, -2.0, -5.0, -9.0};

}  // namespace

TEST(Equalize, HitsTheTargetGainsAndKeepsTimingLengthAndPeak) {
  for (double fs : {16000.0, 48000.0}) {
    const Signal x = eqtest::decaying_noise_rir("r1", fs, static_cast<size_t>(fs), 0.6, 200, 0.0, 7);
    EqApplyOptions o;
    o.measure_output = true;
    const EqResult r = equalize_rir(x, kTarget, o);
    ASSERT_EQ(r.rir.samples.size(), x.samples.size());
    EXPECT_EQ(r.rir.id, "r1");
    EXPECT_EQ(r.rir.sample_rate_hz, fs);
    for (int k = 0; k < kEqNumPoints; ++k) {
      // Measured on the written RIR. The refinement predicts the gains of the uncropped filtered
      // RIR; cropping the filter's pre-ringing and the tail's post-ringing moves band levels by a
      // few hundredths of a dB, so 0.2 dB is ample (the FIR budget is 0.5 dB).
      EXPECT_NEAR(r.after_db[k], kTarget[k], 0.2) << kEqPointsHz[k] << " Hz at " << fs;
      EXPECT_NEAR(r.predicted_db[k], kTarget[k], 0.05) << kEqPointsHz[k];
    }
    EXPECT_EQ(peak_index(r.rir.samples), 200u);  // direct sound in place
    EXPECT_NEAR(std::abs(r.rir.samples[200]), std::abs(x.samples[200]), 1e-6);  // level convention: peak
    EXPECT_FALSE(r.clamped);
  }
}

TEST(Equalize, RefinementIsWhatMakesTheGainsExact) {
  // The single literal design misses the target because neighbouring corrections spill into each
  // octave; this is why refine_iterations defaults to 3.
  const Signal x = eqtest::decaying_noise_rir("r2", 16000, 16000, 0.5, 100, 3.0, 8);
  EqApplyOptions literal;
  literal.refine_iterations = 0;
  literal.measure_output = true;
  const EqResult r0 = equalize_rir(x, kTarget, literal);
  EXPECT_EQ(r0.filters_designed, 1);
  double worst = 0;
  for (int k = 0; k < kEqNumPoints; ++k) worst = std::max(worst, std::abs(r0.after_db[k] - kTarget[k]));
  EXPECT_GT(worst, 0.3);
  EqApplyOptions refined;
  refined.measure_output = true;
  const EqResult r3 = equalize_rir(x, kTarget, refined);
  for (int k = 0; k < kEqNumPoints; ++k) EXPECT_NEAR(r3.after_db[k], kTarget[k], 0.2);
  EXPECT_LE(r3.filters_designed, 1 + refined.refine_iterations + 2);  // documented maximum
}

TEST(Equalize, LevelConventions) {
  const Signal x = eqtest::decaying_noise_rir("r3", 16000, 12000, 0.4, 50, -3.0, 9);
  EqApplyOptions o;
  o.level = EqLevel::kEnergy;
  EXPECT_NEAR(energy(equalize_rir(x, kTarget, o).rir.samples) / energy(x.samples), 1.0, 1e-4);
  o.level = EqLevel::kPeak;
  const EqResult p = equalize_rir(x, kTarget, o);
  double peak_in = 0, peak_out = 0;
  for (float v : x.samples) peak_in = std::max(peak_in, static_cast<double>(std::abs(v)));
  for (float v : p.rir.samples) peak_out = std::max(peak_out, static_cast<double>(std::abs(v)));
  EXPECT_NEAR(peak_out, peak_in, 1e-6);
  // none: the filter is 0 dB at 1 kHz; the 1 kHz octave band level barely moves.
  o.level = EqLevel::kNone;
  o.measure_output = true;
  const EqResult n = equalize_rir(x, kTarget, o);
  EXPECT_NE(energy(n.rir.samples), energy(x.samples));
  EXPECT_THROW(parse_eq_level("loud"), Error);
}

TEST(Equalize, ClampsAbsurdCorrections) {
  const Signal x = eqtest::decaying_noise_rir("r4", 16000, 16000, 0.5, 100, 0.0, 10);
  RelativeGainsDb wild = kTarget;
  wild[0] = 60.0;
  EqApplyOptions o;
  o.max_boost_db = 20.0;
  const EqResult r = equalize_rir(x, wild, o);
  EXPECT_TRUE(r.clamped);
  for (double g : r.node_gains_db) EXPECT_LE(g, 20.0);
  wild[0] = -90.0;
  o.max_cut_db = 50.0;
  const EqResult c = equalize_rir(x, wild, o);
  EXPECT_TRUE(c.clamped);
  for (double g : c.node_gains_db) EXPECT_GE(g, -50.0);
}

TEST(Equalize, ClearErrors) {
  Signal silent;
  silent.id = "s";
  silent.sample_rate_hz = 16000;
  silent.samples.assign(1000, 0.0f);
  EXPECT_THROW(equalize_rir(silent, kTarget, {}), Error);
  Signal low = eqtest::decaying_noise_rir("low", 8000, 8000, 0.5, 10, 0.0, 1);
  EXPECT_THROW(equalize_rir(low, kTarget, {}), Error);
  RelativeGainsDb bad = kTarget;
  bad[2] = NAN;
  const Signal x = eqtest::decaying_noise_rir("x", 16000, 4000, 0.2, 10, 0.0, 2);
  EXPECT_THROW(equalize_rir(x, bad, {}), Error);
}

TEST(Equalize, AnArraysChannelsGetChannelZerosFilterAndKeepTheirTimeAndLevelDifferences) {
  // Channel 1 is channel 0 delayed by 5 samples at half the level, channel 2 another RIR: after
  // the EQ, channel 0 is exactly equalize_rir()'s output, channel 1 is still channel 0's output
  // delayed by 5 samples at half the level (the same filter and scale), and channel 2 is channel
  // 2's input through that filter (its own gains are not matched to the target).
  const Signal x0 = eqtest::decaying_noise_rir("arr", 16000, 8000, 0.5, 200, 0.0, 7);
  Signal x1 = x0;
  std::fill(x1.samples.begin(), x1.samples.end(), 0.0f);
  for (size_t i = 5; i < x0.size(); ++i) x1.samples[i] = 0.5f * x0.samples[i - 5];
  Signal x2 = eqtest::decaying_noise_rir("arr", 16000, 8000, 0.9, 230, 0.0, 8);
  EqApplyOptions o;
  std::vector<Signal> others;
  const EqResult r = equalize_rir_channels({x0, x1, x2}, kTarget, o, &others);
  ASSERT_EQ(others.size(), 2u);
  EXPECT_EQ(r.rir.samples, equalize_rir(x0, kTarget, o).rir.samples);
  double peak = 0.0;
  for (float v : r.rir.samples) peak = std::max(peak, static_cast<double>(std::abs(v)));
  // Away from the ends (the filter's support, the cropped first samples) the relation is exact
  // up to float rounding.
  for (size_t i = 600; i + 600 < x0.size(); ++i) {
    ASSERT_NEAR(others[0].samples[i], 0.5f * r.rir.samples[i - 5], 1e-5 * peak) << "sample " << i;
  }
  EXPECT_EQ(others[1].id, "arr");
  EXPECT_EQ(peak_index(others[1].samples), 230u);
  EXPECT_EQ(others[1].size(), x2.size());
}
