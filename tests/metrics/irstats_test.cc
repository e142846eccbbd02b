// The irstats definition, one irStats.m step at a time (docs/reference/spec-digest.md §1.2), then end to end.
#include "metrics/irstats.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dsp/octave_filter.h"
#include "metrics/rir_metrics.h"
#include "synthetic_rirs.h"
#include "util/error.h"

namespace tsrir {
namespace {

TEST(Irstats, PeakIsFirstMaximumOfTheSquare) {
  size_t ties = 0;
  // A negative peak counts (x^2), and of two equal peaks the first wins (with a tie count).
  EXPECT_EQ(irstats_peak_index({0.1f, -0.9f, 0.5f}, &ties), 1u);
  EXPECT_EQ(ties, 1u);
  EXPECT_EQ(irstats_peak_index({0.1f, 0.7f, -0.7f, 0.2f}, &ties), 1u);
  EXPECT_EQ(ties, 2u);
}

TEST(Irstats, TrapzSubtractsHalfTheEnds) {
  const std::vector<float> x = {1, 2, 3, 4};
  // trapz([4 9 16]) = 4/2 + 9 + 16/2
  EXPECT_DOUBLE_EQ(irstats_trapz_energy(x, 1, 3), 2 + 9 + 8);
  // trapz of one sample is 0 in MATLAB.
  EXPECT_DOUBLE_EQ(irstats_trapz_energy(x, 2, 2), 0.0);
}

TEST(Irstats, DecayCurveIsReversedCumtrapz) {
  // y.^2 = [1 4 9]; flipud -> [9 4 1]; cumtrapz -> [0 6.5 9]; flipud -> [9 6.5 0].
  const std::vector<double> z = irstats_decay_curve({1, 2, 3});
  ASSERT_EQ(z.size(), 3u);
  EXPECT_DOUBLE_EQ(z[0], 9.0);
  EXPECT_DOUBLE_EQ(z[1], 6.5);
  EXPECT_DOUBLE_EQ(z[2], 0.0);
}

// z with 10 log10(z) = -s (k - 1) exactly (k 1-based), plus the trailing zero cumtrapz leaves.
std::vector<double> linear_db_curve(double s_db_per_sample, size_t n) {
  std::vector<double> z(n);
  for (size_t i = 0; i + 1 < n; ++i) z[i] = std::pow(10.0, -s_db_per_sample * (double)i / 10.0);
  z[n - 1] = 0.0;
  return z;
}

TEST(Irstats, CalcDecayCountsSamplesOnTheAnchoredLine) {
  const double fs = 16000;
  // Slope 0.0123 dB/sample: the anchored line p1 (k - 1) first reaches -60 dB at
  // k = 1 + ceil(60 / 0.0123) = 4880, and irStats reports k / fs (one sample more than 60/|p1|).
  const std::vector<double> z = linear_db_curve(0.0123, 8000);
  const IrstatsDecay rt = irstats_calc_decay(z.data(), z.size(), fs, 0, -60);
  EXPECT_TRUE(rt.range_reached);
  EXPECT_DOUBLE_EQ(rt.time_s, (1.0 + std::ceil(60 / 0.0123)) / fs);
  // EDT: 6 x (first k with p1 (k-1) <= -10) / fs.
  const IrstatsDecay edt = irstats_calc_decay(z.data(), z.size(), fs, 0, -10);
  EXPECT_DOUBLE_EQ(edt.time_s, 6.0 * (1.0 + std::ceil(10 / 0.0123)) / fs);
  // y_fit [-5 -25]: the slope is all that matters, 3 x (k for 20 dB).
  const IrstatsDecay t20 = irstats_calc_decay(z.data(), z.size(), fs, -5, -25);
  EXPECT_DOUBLE_EQ(t20.time_s, 3.0 * (1.0 + std::ceil(20 / 0.0123)) / fs);
}

TEST(Irstats, CalcDecayFitsToTheLastSampleWhenMinus60IsNotReached) {
  const double fs = 16000;
  // Falls only 0.005 dB/sample x 7999 = 40 dB: irStats warns and fits to the end; the line's
  // slope still gives 60 dB at k = 1 + 60 / 0.005.
  const std::vector<double> z = linear_db_curve(0.005, 8000);
  const IrstatsDecay rt = irstats_calc_decay(z.data(), z.size(), fs, 0, -60);
  EXPECT_FALSE(rt.range_reached);
  EXPECT_NEAR(rt.time_s, (1.0 + 60 / 0.005) / fs, 1.5 / fs);
}

TEST(Irstats, CalcDecayRejectsRisingCurves) {
  std::vector<double> z = {1, 1, 1, 1, 0};
  EXPECT_TRUE(std::isnan(irstats_calc_decay(z.data(), z.size(), 16000, 0, -60).time_s));
}

TEST(Irstats, DrrAndCteUseTrapzWindowsAroundThePeak) {
  const double fs = 16000;  // C = round(0.0025 fs) = 40, te = 800
  std::vector<float> x(2000, 0.0f);
  x[100] = 1.0f;    // t0
  x[120] = 0.5f;    // inside +-40: direct
  x[150] = 0.25f;   // reverberant for DRR, early for CTE
  x[1000] = 0.1f;   // late
  const IrstatsRatios r = irstats_drr_cte(x, 100, fs);
  // Window ends (x[60], x[140], x[141], x[1999]) are zero, so trapz = plain sums here.
  EXPECT_NEAR(r.drr_db, 10 * std::log10((1.0 + 0.25) / (0.0625 + 0.01)), 1e-5);
  EXPECT_NEAR(r.cte_db, 10 * std::log10((1.0 + 0.25 + 0.0625) / 0.01), 1e-5);
  EXPECT_TRUE(r.warnings.empty());
  // A sample on the window end is halved: x[140] direct end, x[141] reverberant start.
  x[140] = 0.5f;
  x[141] = 0.5f;
  const IrstatsRatios r2 = irstats_drr_cte(x, 100, fs);
  EXPECT_NEAR(r2.drr_db, 10 * std::log10((1.25 + 0.125) / (0.0625 + 0.01 + 0.125)), 1e-5);
}

TEST(Irstats, DirectWindowClampsAtTheFirstSampleAndCteNeedsTe) {
  std::vector<float> x(900, 0.0f);
  x[10] = 1.0f;
  x[850] = 0.1f;
  const IrstatsRatios r = irstats_drr_cte(x, 10, 16000);
  EXPECT_NEAR(r.drr_db, 10 * std::log10(1.0 / 0.01), 1e-5);
  // t0 + te + 1 = 811 < 900: CTE defined; with the peak at 150 it is not.
  EXPECT_TRUE(std::isfinite(r.cte_db));
  std::vector<float> y(900, 0.0f);
  y[150] = 1.0f;
  y[890] = 0.1f;
  const IrstatsRatios r3 = irstats_drr_cte(y, 150, 16000);
  EXPECT_TRUE(std::isnan(r3.cte_db));
  ASSERT_EQ(r3.warnings.size(), 1u);
}

TEST(Irstats, BandsAreThoseOctdsgnRecommends) {
  EXPECT_EQ(irstats_band_centers_hz(16000), (std::vector<double>{125, 250, 500, 1000, 2000}));
  EXPECT_EQ(irstats_band_centers_hz(48000), (std::vector<double>{250, 500, 1000, 2000, 4000, 8000}));
  EXPECT_EQ(metrics_band_centers_hz(16000, MetricsDefinition::kIrstats), irstats_band_centers_hz(16000));
}

TEST(Irstats, MeasureComposesTheSteps) {
  tsrir_test::ExponentialRirSpec spec;
  spec.direct_amplitude = 0.8;
  spec.direct_sample = 200;
  spec.tail_start_sample = 240;
  spec.t60_s = 0.4;
  const Signal rir = tsrir_test::exponential_rir(spec);
  MetricsOptions o;
  o.definition = MetricsDefinition::kIrstats;
  const RirMetrics m = measure_rir(rir, o);
  const size_t t0 = irstats_peak_index(rir.samples);
  EXPECT_EQ(t0, 200u);
  EXPECT_EQ(m.onset_sample, t0);
  ASSERT_EQ(m.bands.size(), 5u);
  // Causal ANSI octave filter, decay curve over the whole file, evaluated from the broadband t0.
  for (const BandMetrics& b : m.bands) {
    const std::vector<double> y = sos_filter(ansi_octave_filter(b.center_hz, 16000, 3), rir.samples);
    const std::vector<double> z = irstats_decay_curve(y);
    EXPECT_DOUBLE_EQ(b.rt_s, irstats_calc_decay(z.data() + t0, z.size() - t0, 16000, 0, -60).time_s);
    EXPECT_DOUBLE_EQ(b.edt_s, irstats_calc_decay(z.data() + t0, z.size() - t0, 16000, 0, -10).time_s);
  }
  EXPECT_DOUBLE_EQ(m.t60_s, 0.5 * (m.band(500)->rt_s + m.band(1000)->rt_s));
  EXPECT_DOUBLE_EQ(m.edt_s, 0.5 * (m.band(500)->edt_s + m.band(1000)->edt_s));
  const IrstatsRatios r = irstats_drr_cte(rir.samples, t0, 16000);
  EXPECT_DOUBLE_EQ(m.drr_db, r.drr_db);
  EXPECT_DOUBLE_EQ(m.c50_db, r.cte_db);
  // A clean 0.4 s decay reaches -60 dB inside 1 s: the direct fit lands near the true T60 (the
  // direct sound steepens the start; 10 % covers it and the causal filter's ringing).
  EXPECT_NEAR(m.t60_s, 0.4, 0.04);
}

TEST(Irstats, LongDecayWarnsThatMinus60IsNotReached) {
  tsrir_test::ExponentialRirSpec spec;
  spec.t60_s = 3.0;
  MetricsOptions o;
  o.definition = MetricsDefinition::kIrstats;
  const RirMetrics m = measure_rir(tsrir_test::exponential_rir(spec), o);
  bool warned = false;
  for (const std::string& w : m.warnings) warned = warned || w.find("never reaches -60") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Irstats, RejectsLowRatesAndShortFiles) {
  MetricsOptions o;
  o.definition = MetricsDefinition::kIrstats;
  Signal s;
  s.id = "lowrate";
  s.sample_rate_hz = 4000;
  s.samples.assign(4000, 0.0f);
  s.samples[10] = 1;
  EXPECT_THROW(measure_rir(s, o), Error);
  s.sample_rate_hz = 16000;
  s.samples.assign(700, 0.0f);  // te = 800 samples
  s.samples[10] = 1;
  try {
    measure_rir(s, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lowrate"), std::string::npos);
  }
}

}  // namespace
}  // namespace tsrir
