// The iso definition against synthetic RIRs with known answers (tests/metrics/synthetic_rirs.h).
#include "metrics/rir_metrics.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

#include "synthetic_rirs.h"
#include "util/error.h"

namespace tsrir {
namespace {

using tsrir_test::ExponentialRirSpec;

bool has_warning(const RirMetrics& m, const std::string& part) {
  for (const std::string& w : m.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

TEST(IsoMetrics, BandsBelowNyquist) {
  EXPECT_EQ(metrics_band_centers_hz(16000, MetricsDefinition::kIso),
            (std::vector<double>{62.5, 125, 250, 500, 1000, 2000, 4000}));
  EXPECT_EQ(metrics_band_centers_hz(48000, MetricsDefinition::kIso).size(), 8u);
  EXPECT_EQ(parse_metrics_definition("irstats"), MetricsDefinition::kIrstats);
  EXPECT_THROW(parse_metrics_definition("sabine"), Error);
}

// White noise under one exponential envelope: every band decays with the same T60. A single noise
// realisation's decay scatters around the envelope, more in narrow bands, so the estimator's bias
// is checked on the mean over 24 realisations (within 2 %) and single RIRs against a bound on the
// scatter. Narrow low bands are covered by the deterministic tones of RecoversPerBandT60.
TEST(IsoMetrics, RecoversT60OfAnExponentialDecay) {
  const double t60 = 0.8;
  constexpr int kSeeds = 24;
  std::map<double, std::array<double, 3>> band_sum;  // T20, T30, EDT
  std::array<double, 3> broadband_sum = {0, 0, 0};
  for (int seed = 1; seed <= kSeeds; ++seed) {
    ExponentialRirSpec spec;
    spec.t60_s = t60;
    spec.duration_s = 1.5;
    spec.seed = seed;
    const RirMetrics m = measure_rir(exponential_rir(spec));
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    EXPECT_NEAR(m.broadband.t30_s, t60, 0.02 * t60);
    broadband_sum[0] += m.broadband.t20_s;
    broadband_sum[1] += m.broadband.t30_s;
    broadband_sum[2] += m.broadband.edt_s;
    for (const BandMetrics& b : m.bands) {
      if (b.center_hz < 1000) continue;
      // Single-realisation scatter of T30 measured over these seeds: sd 2 % at 1 kHz, 0.9 % at
      // 4 kHz; 3 sd = 6 %.
      EXPECT_NEAR(b.t30_s, t60, 0.06 * t60) << b.center_hz;
      band_sum[b.center_hz][0] += b.t20_s;
      band_sum[b.center_hz][1] += b.t30_s;
      band_sum[b.center_hz][2] += b.edt_s;
    }
  }
  for (double v : broadband_sum) EXPECT_NEAR(v / kSeeds, t60, 0.02 * t60);
  ASSERT_EQ(band_sum.size(), 3u);
  for (const auto& [fc, sums] : band_sum) {
    EXPECT_NEAR(sums[0] / kSeeds, t60, 0.02 * t60) << "T20 " << fc;
    EXPECT_NEAR(sums[1] / kSeeds, t60, 0.02 * t60) << "T30 " << fc;
    // EDT spans only 10 dB (single-RIR sd 7 % at 1 kHz): its mean has a standard error of 1.5 %,
    // so 3 % keeps the bias check meaningful without flaking.
    EXPECT_NEAR(sums[2] / kSeeds, t60, 0.03 * t60) << "EDT " << fc;
  }
}

// Different decay per octave band, generated as damped tones at the band centres (no filtering
// involved), so each band's decay is exactly exponential.
TEST(IsoMetrics, RecoversPerBandT60) {
  const std::vector<double> centers = {62.5, 125, 250, 500, 1000, 2000, 4000};
  const std::vector<double> t60 = {1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4};
  const Signal rir = tsrir_test::multiband_rir(16000, 1.5, centers, t60, 100, 0.0, 3);
  const RirMetrics m = measure_rir(rir);
  ASSERT_EQ(m.bands.size(), centers.size());
  for (size_t b = 0; b < centers.size(); ++b) {
    EXPECT_NEAR(m.bands[b].t30_s, t60[b], 0.02 * t60[b]) << centers[b];
    EXPECT_NEAR(m.bands[b].t20_s, t60[b], 0.02 * t60[b]) << centers[b];
    EXPECT_NEAR(m.bands[b].edt_s, t60[b], 0.02 * t60[b]) << centers[b];
  }
  EXPECT_NEAR(m.t60_s, 0.65, 0.02 * 0.65);
}

TEST(IsoMetrics, NoiseFloorIsTruncatedAndCompensated) {
  const std::vector<double> centers = {62.5, 125, 250, 500, 1000, 2000, 4000};
  const std::vector<double> t60 = {1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4};
  // Noise rms 1e-5 against band amplitudes ~0.1: about 60 dB below the peak of each band.
  // White noise rms 5e-4 against tones of amplitude 0.1: 47 (4 kHz) to 65 dB (62.5 Hz) peak-to-
  // noise in the bands, just above ISO's 45 dB for T30 at the top.
  const double noise_rms = 5e-4;
  const Signal rir = tsrir_test::multiband_rir(16000, 1.5, centers, t60, 100, noise_rms, 3);
  const RirMetrics m = measure_rir(rir);
  MetricsOptions raw;
  raw.lundeby = false;
  const RirMetrics r = measure_rir(rir, raw);
  double err_lundeby = 0, err_raw = 0;
  for (size_t b = 0; b < centers.size(); ++b) {
    EXPECT_NEAR(m.bands[b].t30_s, t60[b], 0.02 * t60[b]) << centers[b];
    EXPECT_NEAR(m.bands[b].t20_s, t60[b], 0.02 * t60[b]) << centers[b];
    EXPECT_GT(m.bands[b].dynamic_range_db, 45) << centers[b];
    EXPECT_LT(m.bands[b].dynamic_range_db, 70) << centers[b];
    err_lundeby += std::abs(m.bands[b].t30_s / t60[b] - 1);
    err_raw += std::abs(r.bands[b].t30_s / t60[b] - 1);
  }
  // Integrating the noise bends the EDC: without noise handling T30 is far off in the upper
  // bands (+24 % at 2 kHz, x7 at 4 kHz).
  EXPECT_GT(err_raw, 10 * err_lundeby);
  EXPECT_GT(r.band(2000)->t30_s, 1.1 * 0.5);
}

TEST(IsoMetrics, TooLittleDynamicRangeForT30ReportsT20) {
  ExponentialRirSpec spec;
  spec.t60_s = 0.6;
  spec.tail_amplitude = 0.1;
  spec.noise_rms = 0.1 * std::pow(10.0, -40.0 / 20);  // 40 dB below the decay's start
  const RirMetrics m = measure_rir(exponential_rir(spec));
  const BandMetrics* b = m.band(1000);
  ASSERT_NE(b, nullptr);
  EXPECT_TRUE(std::isnan(b->t30_s));
  EXPECT_NEAR(b->t20_s, 0.6, 0.03 * 0.6);
  EXPECT_DOUBLE_EQ(b->rt_s, b->t20_s);
  EXPECT_TRUE(has_warning(m, "1000 Hz: dynamic range too small for T30"));
  EXPECT_DOUBLE_EQ(m.t60_s, 0.5 * (m.band(500)->t20_s + m.band(1000)->t20_s));
  // Below ~30 dB nothing is reported at all.
  spec.noise_rms = 0.1 * std::pow(10.0, -25.0 / 20);
  const RirMetrics worse = measure_rir(exponential_rir(spec));
  EXPECT_TRUE(std::isnan(worse.band(1000)->t20_s));
  EXPECT_TRUE(std::isnan(worse.t60_s));
  EXPECT_TRUE(has_warning(worse, "too small for T20 and T30"));
}

// Direct impulse at 10 ms, tail from 3 ms later (outside the +-2.5 ms direct window), so DRR and
// C50 are known from the generated samples themselves.
struct DirectCase {
  Signal rir;
  double drr_db, c50_db;
};
DirectCase direct_case(double noise_rms) {
  ExponentialRirSpec spec;
  spec.direct_sample = 160;
  spec.direct_amplitude = 0.5;
  spec.tail_start_sample = 160 + 48;
  spec.tail_amplitude = 0.05;
  spec.t60_s = 0.5;
  spec.noise_rms = noise_rms;
  std::vector<double> clean;
  DirectCase c;
  c.rir = exponential_rir(spec, &clean);
  const size_t n = clean.size();
  c.drr_db = 10 * std::log10(tsrir_test::energy(clean, 120, 201) / tsrir_test::energy(clean, 201, n));
  c.c50_db = 10 * std::log10(tsrir_test::energy(clean, 160, 960) / tsrir_test::energy(clean, 960, n));
  return c;
}

TEST(IsoMetrics, DrrAndC50ByConstruction) {
  const DirectCase c = direct_case(0.0);
  const RirMetrics m = measure_rir(c.rir);
  EXPECT_EQ(m.peak_sample, 160u);
  EXPECT_EQ(m.onset_sample, 160u);
  EXPECT_NEAR(m.drr_db, c.drr_db, 0.2);
  EXPECT_NEAR(m.c50_db, c.c50_db, 0.2);
}

TEST(IsoMetrics, DrrAndC50WithNoiseFloor) {
  // Noise 20 dB below the tail's start: over 1 s its energy is ~30 % of the reverberant energy.
  const DirectCase c = direct_case(0.05 * std::pow(10.0, -20.0 / 20));
  const RirMetrics m = measure_rir(c.rir);
  EXPECT_NEAR(m.drr_db, c.drr_db, 0.2);
  EXPECT_NEAR(m.c50_db, c.c50_db, 0.2);
  MetricsOptions raw;
  raw.lundeby = false;
  const RirMetrics r = measure_rir(c.rir, raw);
  // Uncompensated, the noise is counted as reverberation: DRR -1 dB, C50 -2.9 dB off.
  EXPECT_GT(std::abs(r.drr_db - c.drr_db), 0.5);
  EXPECT_GT(std::abs(r.c50_db - c.c50_db), 1.5);
}

TEST(IsoMetrics, DirectWindowIsConfigurable) {
  const DirectCase c = direct_case(0.0);
  MetricsOptions o;
  o.direct_post_ms = 10.0;  // now the first 7 ms of the tail count as direct
  const RirMetrics m = measure_rir(c.rir, o);
  EXPECT_GT(m.drr_db, c.drr_db + 0.1);
}

TEST(IsoMetrics, BadInputNamesTheRir) {
  auto expect_error = [](Signal s, const std::string& part) {
    try {
      measure_rir(s);
      FAIL() << "no error for " << part;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("'" + s.id + "'"), std::string::npos) << what;
      EXPECT_NE(what.find(part), std::string::npos) << what;
    }
  };
  Signal s;
  s.id = "room7-pos3";
  s.sample_rate_hz = 16000;
  expect_error(s, "no samples");
  s.samples.assign(16000, 0.0f);
  expect_error(s, "silent");
  s.samples[100] = NAN;
  expect_error(s, "NaN");
  s.samples.assign(500, 0.0f);
  s.samples[10] = 1.0f;
  expect_error(s, "too short");
  s.samples.assign(16000, 0.0f);
  s.samples[10] = 1.0f;
  s.sample_rate_hz = 0;
  expect_error(s, "sample rate");
}

TEST(IsoMetrics, PureImpulseIsMeasurableButHasNoDecay) {
  Signal s;
  s.id = "dirac";
  s.sample_rate_hz = 16000;
  s.samples.assign(16000, 0.0f);
  s.samples[100] = 1.0f;
  const RirMetrics m = measure_rir(s);
  EXPECT_TRUE(std::isinf(m.drr_db) || std::isnan(m.drr_db));
  EXPECT_FALSE(m.warnings.empty());
}

}  // namespace
}  // namespace tsrir

namespace tsrir {
namespace {

TEST(IsoMetrics, LowRateHasNoMidBandT60) {
  tsrir_test::ExponentialRirSpec spec;
  spec.sample_rate_hz = 2000;  // the 1 kHz octave does not fit below 1 kHz Nyquist
  spec.direct_sample = spec.tail_start_sample = 20;
  const RirMetrics m = measure_rir(tsrir_test::exponential_rir(spec));
  EXPECT_EQ(m.band(1000), nullptr);
  EXPECT_TRUE(std::isnan(m.t60_s));
  EXPECT_TRUE(has_warning(m, "not both measured"));
  EXPECT_NEAR(m.broadband.t30_s, 0.5, 0.03 * 0.5);
}

}  // namespace
}  // namespace tsrir

namespace tsrir {
namespace {

TEST(IsoMetrics, BroadbandDecayOverNoiseFloor) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    tsrir_test::ExponentialRirSpec spec;
    spec.t60_s = 0.6;
    spec.seed = seed;
    spec.noise_rms = 0.1 * std::pow(10.0, -50.0 / 20);  // 50 dB below the decay's start
    const RirMetrics m = measure_rir(tsrir_test::exponential_rir(spec));
    EXPECT_NEAR(m.broadband.t30_s, 0.6, 0.02 * 0.6) << seed;
    EXPECT_NEAR(m.broadband.t20_s, 0.6, 0.02 * 0.6) << seed;
    EXPECT_NEAR(m.broadband.dynamic_range_db, 50.0, 3.0) << seed;
    MetricsOptions raw;
    raw.lundeby = false;
    // Integrated noise bends the raw EDC upwards well before -35 dB.
    EXPECT_GT(measure_rir(tsrir_test::exponential_rir(spec), raw).broadband.t30_s, 0.6 * 1.04) << seed;
  }
}

}  // namespace
}  // namespace tsrir
