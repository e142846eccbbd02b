// Set statistics, the table and JSON outputs and the Table-1 comparison.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "metrics/metric_columns.h"
#include "metrics/metrics_report.h"
#include "metrics/metrics_summary.h"
#include "util/error.h"

namespace tsrir {
namespace {

RirMetrics make(const std::string& id, double t60, double drr, double edt, double c50) {
  RirMetrics m;
  m.id = id;
  m.t60_s = t60;
  m.drr_db = drr;
  m.edt_s = edt;
  m.c50_db = c50;
  m.d50_percent = 70.5;
  m.c80_db = c50 + 2;
  BandMetrics b;
  b.center_hz = 500;
  b.t20_s = 0.5;
  b.t30_s = 0.55;
  b.edt_s = 0.45;
  b.rt_s = 0.55;
  m.bands.push_back(b);
  b.center_hz = 62.5;
  b.t30_s = kMetricsNaN;
  m.bands.push_back(b);
  return m;
}

TEST(MetricsSummary, MeanStdMedianSkipNaN) {
  MetricsSummary s;
  s.add(make("a", 1.0, -2, 0.5, 3));
  s.add(make("b", 2.0, -4, 0.7, kMetricsNaN));
  s.add(make("c", 4.0, -6, 0.9, 5));
  s.add(make("d", 7.0, -8, 1.1, 7));
  const ParameterStats t = s.stats(metric_column_index("T60"));
  EXPECT_EQ(t.count, 4u);
  EXPECT_DOUBLE_EQ(t.mean, 3.5);
  EXPECT_DOUBLE_EQ(t.median, 3.0);
  EXPECT_NEAR(t.std, std::sqrt((6.25 + 2.25 + 0.25 + 12.25) / 3), 1e-12);
  const ParameterStats c = s.stats(metric_column_index("C50"));
  EXPECT_EQ(c.count, 3u);
  EXPECT_DOUBLE_EQ(c.median, 5.0);
  EXPECT_EQ(s.num_rirs(), 4u);
  EXPECT_TRUE(std::isnan(MetricsSummary().stats(metric_column_index("DRR")).mean));
}

TEST(MetricsReport, TableHasHeaderAndBandColumns) {
  std::ostringstream out;
  MetricsReport r(out, MetricsFormat::kTable, /*with_bands=*/true);
  r.add(make("rir1", 0.5, -3.25, 0.4, 6));
  r.add(make("rir2", 0.75, 1, 0.6, kMetricsNaN));
  r.finish();
  EXPECT_EQ(out.str(),
            "# id T60 EDT DRR C50 D50 C80 T20_500 T30_500 EDT_500 T20_62.5 T30_62.5 EDT_62.5\n"
            "rir1 0.5 0.4 -3.25 6 70.5 8 0.5 0.55 0.45 0.5 nan 0.45\n"
            "rir2 0.75 0.6 1 nan 70.5 nan 0.5 0.55 0.45 0.5 nan 0.45\n");
  std::ostringstream plain;
  MetricsReport p(plain, MetricsFormat::kTable, false);
  p.add(make("x", 1, 2, 3, 4));
  EXPECT_EQ(plain.str(), "# id T60 EDT DRR C50 D50 C80\nx 1 3 2 4 70.5 6\n");
}

TEST(MetricsReport, JsonCarriesRirsBandsWarningsSummaryAndErrors) {
  std::ostringstream out;
  {
    MetricsReport r(out, MetricsFormat::kJson, false);
    RirMetrics m = make("rir\"1", 0.5, -3, 0.4, 6);
    m.warnings.push_back("62.5 Hz: dynamic range too small for T30");
    r.add(m);
    r.add(make("rir2", 1.5, -5, 0.6, 8));
    r.add_error("bad", "RIR 'bad': silent");
    r.finish();
  }
  const std::string j = out.str();
  // Compact checks of the structure (the writer itself is tested in util).
  auto compact = [](std::string s) {
    std::string o;
    for (char c : s)
      if (c != ' ' && c != '\n') o += c;
    return o;
  };
  const std::string c = compact(j);
  EXPECT_EQ(c.rfind("{\"rirs\":[{\"id\":\"rir\\\"1\",\"T60\":0.5,\"EDT\":0.4,\"DRR\":-3,\"C50\":6,\"D50\":70.5,\"C80\":8,\"bands\":{\"500\":{\"T20\":0.5,\"T30\":0.55,\"EDT\":0.45", 0), 0u) << j;
  EXPECT_NE(c.find("\"62.5\":{\"T20\":0.5,\"T30\":null"), std::string::npos) << j;
  EXPECT_NE(c.find("\"warnings\":[\"62.5Hz:dynamicrangetoosmallforT30\"]"), std::string::npos) << j;
  EXPECT_NE(c.find("\"summary\":{\"count\":2,\"T60\":{\"mean\":1,\"std\":0.7071067812,\"median\":1,\"count\":2}"),
            std::string::npos) << j;
  EXPECT_NE(c.find("\"errors\":[{\"id\":\"bad\",\"error\":\"RIR'bad':silent\"}]"), std::string::npos) << j;
  EXPECT_EQ(c.back(), '}');
}

TEST(MetricsReport, ParsesFormats) {
  EXPECT_EQ(parse_metrics_format("json"), MetricsFormat::kJson);
  EXPECT_THROW(parse_metrics_format("csv"), Error);
  EXPECT_EQ(band_label(62.5), "62.5");
  EXPECT_EQ(band_label(16000), "16000");
}

NamedSummary set(const std::string& name, std::vector<RirMetrics> rirs) {
  NamedSummary s{name, {}};
  for (const auto& m : rirs) s.summary.add(m);
  return s;
}

TEST(ReferenceTable, MeansDiffsAndClosestSet) {
  // Paper Table 1 numbers as single-RIR "sets": Real, GAS, GSR(GAS).
  const NamedSummary real = set("real", {make("r", 1.0207, -6.3945, 0.8572, 3.4886)});
  const std::vector<NamedSummary> sets = {set("gas", {make("g", 0.9553, -4.7277, 0.8846, 4.7536)}),
                                          set("gsr_gas", {make("t", 1.6433, -6.6491, 0.8483, 3.4907)})};
  EXPECT_EQ(closest_set(real, sets, metric_column_index("T60")), 0);
  EXPECT_EQ(closest_set(real, sets, metric_column_index("DRR")), 1);
  EXPECT_EQ(closest_set(real, sets, metric_column_index("EDT")), 1);
  EXPECT_EQ(closest_set(real, sets, metric_column_index("C50")), 1);
  std::ostringstream text;
  write_reference_table(text, real, sets, "irstats");
  const std::string t = text.str();
  EXPECT_NE(t.find("0.9553 (0.0654)*"), std::string::npos) << t;
  EXPECT_NE(t.find("-4.7277 (1.6668) "), std::string::npos) << t;
  EXPECT_NE(t.find("-6.6491 (0.2546)*"), std::string::npos) << t;
  EXPECT_NE(t.find("3.4907 (0.0021)*"), std::string::npos) << t;
  EXPECT_NE(t.find("1.0207"), std::string::npos) << t;
  std::ostringstream json;
  write_reference_json(json, real, sets, "irstats");
  std::string c;
  for (char ch : json.str())
    if (ch != ' ' && ch != '\n') c += ch;
  EXPECT_NE(c.find("\"definition\":\"irstats\",\"reference\":{\"name\":\"real\",\"count\":1,\"T60\":{\"mean\":1.0207"),
            std::string::npos) << c;
  EXPECT_NE(c.find("\"name\":\"gas\",\"count\":1,\"T60\":{\"mean\":0.9553,\"std\":null,\"median\":0.9553,\"count\":1,\"diff\":0.0654"),
            std::string::npos) << c;
  EXPECT_NE(c.find("\"closest\":true"), std::string::npos);
}

}  // namespace
}  // namespace tsrir
