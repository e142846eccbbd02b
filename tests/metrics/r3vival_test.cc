// Real RIRs: the R3VIVAL lab set (../shared/data/rirs/r3vival). Per-condition medians of the
// per-band T30 (iso definition, default noise handling) must agree with the published-plot-
// consistent T30_per_condition_estimated.csv there ("Schroeder -5..-35 dB, tail noise
// subtracted") within 5 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "io/rir_set.h"
#include "metrics/rir_metrics.h"
#include "util/parallel.h"

namespace tsrir {
namespace {

namespace fs = std::filesystem;

const std::string kDir = std::string(TSRIR_SOURCE_DIR) + "/../shared/data/rirs/r3vival";

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

TEST(R3vival, T30MediansPerConditionMatchTheCsv) {
  const std::string csv_path = kDir + "/T30_per_condition_estimated.csv";
  if (!fs::exists(csv_path)) GTEST_SKIP() << "R3VIVAL data not found at " << kDir << " (shared data absent)";
  // condition -> T30 for 250, 500, 1000, 2000, 4000 Hz
  const std::vector<double> bands = {250, 500, 1000, 2000, 4000};
  std::map<std::string, std::vector<double>> expected;
  std::ifstream csv(csv_path);
  std::string line;
  std::getline(csv, line);  // header
  while (std::getline(csv, line)) {
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::string cond, n, v;
    std::getline(ss, cond, ',');
    std::getline(ss, n, ',');
    while (std::getline(ss, v, ',')) expected[cond].push_back(std::stod(v));
    ASSERT_EQ(expected[cond].size(), bands.size()) << line;
  }
  ASSERT_EQ(expected.size(), 5u);

  std::vector<RirRef> refs;
  for (const auto& entry : fs::directory_iterator(kDir)) {
    if (entry.path().extension() == ".wav") refs.push_back(read_rir_refs(entry.path().string(), nullptr)[0]);
  }
  ASSERT_EQ(refs.size(), 170u);
  std::vector<RirMetrics> results(refs.size());
  parallel_for(refs.size(), 2, [&](size_t i) { results[i] = measure_rir(load_rir(refs[i])); });

  for (const auto& [cond, want] : expected) {
    std::vector<std::vector<double>> per_band(bands.size());
    for (const RirMetrics& m : results) {
      if (m.id.find("Absorptive_" + cond + "_") == std::string::npos) continue;
      for (size_t b = 0; b < bands.size(); ++b) {
        const BandMetrics* bm = m.band(bands[b]);
        ASSERT_NE(bm, nullptr);
        // Every file has > 45 dB of range in these bands: T30 must exist, not fall back to T20.
        ASSERT_TRUE(std::isfinite(bm->t30_s)) << m.id << " " << bands[b];
        per_band[b].push_back(bm->t30_s);
      }
    }
    ASSERT_EQ(per_band[0].size(), 34u) << cond;
    for (size_t b = 0; b < bands.size(); ++b) {
      const double got = median(per_band[b]);
      // 5 %: the tolerance. The CSV is rounded to 10 ms (up to 2 % at 0.26 s), and its
      // band filters are unknown; our medians are within 4 % (largest: 250 Hz, condition 025).
      EXPECT_NEAR(got, want[b], 0.05 * want[b]) << "condition " << cond << ", " << bands[b] << " Hz";
    }
  }
}

}  // namespace
}  // namespace tsrir
