// D50 and C80, the two parameters added through the metric column table (metric_columns.h), against
// closed forms: for a sampled exponential decay h[k] = a^k the energies are geometric series,
// S(i, j) = sum_{k=i..j} r^k = (r^i - r^(j+1)) / (1 - r) with r = a^2, so the expected values come
// from a formula, not from the summation code under test. Several decay times and rates.
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/metric_columns.h"
#include "metrics/metrics_summary.h"
#include "metrics/rir_metrics.h"

namespace tsrir {
namespace {

// r^k with r = a^2 for an amplitude decay of 60 dB in t60_s.
double energy_ratio_per_sample(double t60_s, double fs) { return std::pow(10.0, -6.0 / (t60_s * fs)); }

double series(double r, long i, long j) { return (std::pow(r, i) - std::pow(r, j + 1)) / (1.0 - r); }

Signal decay(double t60_s, double fs, long length, long pre_zeros) {
  Signal s;
  s.id = "decay";
  s.sample_rate_hz = fs;
  s.samples.assign(pre_zeros + length, 0.0f);
  const double a = std::sqrt(energy_ratio_per_sample(t60_s, fs));
  for (long k = 0; k < length; ++k) s.samples[pre_zeros + k] = (float)std::pow(a, k);
  return s;
}

struct Case {
  double t60_s;
  double fs;
};
const Case kCases[] = {{0.3, 16000}, {0.8, 16000}, {1.5, 48000}, {0.5, 8000}};

// iso without Lundeby: the onset is the first sample (the peak), early = h[0, te), late = h[te, end).
TEST(D50C80, IsoMatchesTheGeometricSeries) {
  for (const Case& c : kCases) {
    const long length = std::lround(1.2 * c.t60_s * c.fs);
    MetricsOptions o;
    o.lundeby = false;
    const RirMetrics m = measure_rir(decay(c.t60_s, c.fs, length, 0), o);
    const double r = energy_ratio_per_sample(c.t60_s, c.fs);
    const long n50 = std::lround(0.050 * c.fs), n80 = std::lround(0.080 * c.fs);
    const double d50 = 100.0 * series(r, 0, n50 - 1) / series(r, 0, length - 1);
    const double c80 = 10.0 * std::log10(series(r, 0, n80 - 1) / series(r, n80, length - 1));
    EXPECT_NEAR(m.d50_percent, d50, 1e-4) << c.t60_s << " s at " << c.fs;
    EXPECT_NEAR(m.c80_db, c80, 1e-4) << c.t60_s << " s at " << c.fs;
    // Sanity against the continuous-time values 1 - 10^(-6 t / T60) (D50) for a long decay.
    EXPECT_NEAR(m.d50_percent, 100.0 * (1.0 - std::pow(10.0, -6.0 * 0.05 / c.t60_s)), 1.0);
  }
}

// irstats: t0 = the peak, early = trapz over [t0 - 2.5 ms, t0 + te], late = trapz over (t0 + te, end].
// With zeros before the peak, trapz = series minus half of each end sample.
TEST(D50C80, IrstatsMatchesTheTrapezoidalSeries) {
  for (const Case& c : kCases) {
    const long length = std::lround(1.2 * c.t60_s * c.fs), pre = std::lround(0.01 * c.fs);
    MetricsOptions o;
    o.definition = MetricsDefinition::kIrstats;
    const RirMetrics m = measure_rir(decay(c.t60_s, c.fs, length, pre), o);
    const double r = energy_ratio_per_sample(c.t60_s, c.fs);
    auto trapz = [&](long i, long j) { return series(r, i, j) - 0.5 * (std::pow(r, i) + std::pow(r, j)); };
    const long n50 = std::lround(0.050 * c.fs), n80 = std::lround(0.080 * c.fs);
    // early starts in the zeros before the peak: its first sample is 0, the series starts at k = 0
    // with a full (not halved) weight.
    auto early = [&](long te) { return series(r, 0, te) - 0.5 * std::pow(r, te); };
    const double d50 = 100.0 * early(n50) / (early(n50) + trapz(n50 + 1, length - 1));
    const double c80 = 10.0 * std::log10(early(n80) / trapz(n80 + 1, length - 1));
    EXPECT_NEAR(m.d50_percent, d50, 1e-4) << c.t60_s << " s at " << c.fs;
    EXPECT_NEAR(m.c80_db, c80, 1e-4) << c.t60_s << " s at " << c.fs;
  }
}

TEST(D50C80, TooShortForTheLimitIsNaNWithAWarning) {
  // 60 ms: enough for C50's window, not for C80's.
  MetricsOptions o;
  o.lundeby = false;
  const RirMetrics m = measure_rir(decay(0.3, 16000, 960, 0), o);
  EXPECT_TRUE(std::isfinite(m.d50_percent));
  EXPECT_TRUE(std::isnan(m.c80_db));
  bool warned = false;
  for (const std::string& w : m.warnings) warned |= w.rfind("C80:", 0) == 0;
  EXPECT_TRUE(warned);
}

TEST(MetricColumns, EachParameterIsDeclaredOnceAndReachesTheSummary) {
  const auto& columns = metric_columns();
  for (size_t i = 0; i < columns.size(); ++i) {
    EXPECT_EQ(metric_column_index(columns[i].name), i);
    EXPECT_NE(std::string(columns[i].iso_definition), "");
    EXPECT_NE(std::string(columns[i].irstats_definition), "");
  }
  // The paper's Table 1 order.
  std::vector<std::string> paper;
  for (size_t c : paper_table_columns()) paper.push_back(columns[c].name);
  EXPECT_EQ(paper, (std::vector<std::string>{"T60", "DRR", "EDT", "C50"}));
  EXPECT_EQ(summary_columns().size(), columns.size());
  RirMetrics m;
  m.d50_percent = 42.0;
  m.c80_db = 3.0;
  MetricsSummary s;
  s.add(m);
  EXPECT_DOUBLE_EQ(s.stats("D50").mean, 42.0);
  EXPECT_DOUBLE_EQ(s.stats("C80").mean, 3.0);
  EXPECT_EQ(s.stats("T60").count, 0u);
}

}  // namespace
}  // namespace tsrir
