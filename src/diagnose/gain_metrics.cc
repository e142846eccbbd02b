#include "diagnose/gain_metrics.h"

#include <cctype>
#include <cmath>

#include "metrics/metric_columns.h"
#include "util/error.h"

namespace tsrir::diagnose {
namespace {

double band_mean_abs(const BandValues& a, const BandValues& b) {
  double s = 0.0;
  int c = 0;
  for (int k = 0; k < kNumOctaveBands; ++k) {
    if (std::isfinite(a[k]) && std::isfinite(b[k])) { s += std::abs(a[k] - b[k]); ++c; }
  }
  return c ? s / c : NAN;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The own metrics, in OwnMetric order.
std::vector<GainMetric> own_metrics() {
  return {
      {"t30_per_band", "s", 0.02, [](const RirFeatures& m, const RirFeatures& s) { return band_mean_abs(m.t30_s, s.t30_s); }},
      {"level_per_band", "dB", 0.5, [](const RirFeatures& m, const RirFeatures& s) { return band_mean_abs(m.level_db, s.level_db); }},
      {"lf_spectral_distance", "dB", 0.5,
       [](const RirFeatures& m, const RirFeatures& s) { return lf_spectral_distance_db(m.lf_spectrum_db, s.lf_spectrum_db, 30.0); }},
      // Over the persistence windows within the measurement's active part.
      {"lf_persistence", "", 0.05,
       [](const RirFeatures& m, const RirFeatures& s) {
         const size_t pairs = persistence_pairs_in_span(m);
         return std::abs(mean_persistence(m, pairs) - mean_persistence(s, pairs));
       }},
      {"onset", "ms", 0.1, [](const RirFeatures& m, const RirFeatures& s) { return 1e3 * std::abs(m.onset_s - s.onset_s); }},
      // In the measurement's last 10 % above digital silence, for both.
      {"tail_level", "dB", 1.0,
       [](const RirFeatures& m, const RirFeatures& s) {
         return std::abs(tail_level_in_window_db(m, m) - tail_level_in_window_db(s, m));
       }},
      {"echo_density", "", 0.01, nullptr},
  };
}

struct Table {
  std::vector<GainMetric> metrics;
  std::vector<size_t> own_index;     // OwnMetric -> index
  std::vector<size_t> column_index;  // metric_columns() index -> index
};

const Table& table() {
  static const Table t = [] {
    Table out;
    const std::vector<GainMetric> own = own_metrics();
    out.own_index.assign(own.size(), 0);
    // Per-band decay and level first, then the table's single numbers, then the rest.
    for (size_t k = 0; k < 2; ++k) { out.own_index[k] = out.metrics.size(); out.metrics.push_back(own[k]); }
    for (const MetricColumn& c : metric_columns()) {
      out.column_index.push_back(out.metrics.size());
      const double RirMetrics::*value = c.value;
      out.metrics.push_back({lower(c.name), c.unit, unit_jnd(c.unit), [value](const RirFeatures& m, const RirFeatures& s) {
                               return std::abs(m.metrics.*value - s.metrics.*value);
                             }});
    }
    for (size_t k = 2; k < own.size(); ++k) { out.own_index[k] = out.metrics.size(); out.metrics.push_back(own[k]); }
    return out;
  }();
  return t;
}

}  // namespace

double unit_jnd(const std::string& unit) {
  if (unit == "dB") return 1.0;
  if (unit == "s") return 0.02;
  if (unit == "%") return 5.0;
  return 0.0;
}

GainMetricId GainMetricId::own(OwnMetric metric) { return GainMetricId(table().own_index.at(static_cast<size_t>(metric))); }

GainMetricId GainMetricId::column(const std::string& table_name) {
  return GainMetricId(table().column_index.at(metric_column_index(table_name)));
}

GainMetricId GainMetricId::named(const std::string& name) {
  const auto& metrics = table().metrics;
  for (size_t k = 0; k < metrics.size(); ++k) {
    if (metrics[k].name == name) return GainMetricId(k);
  }
  throw Error("rir-diagnose: unknown gain metric '" + name + "'");
}

const std::vector<GainMetric>& gain_metrics() { return table().metrics; }

const GainMetric& gain_metric(GainMetricId id) { return table().metrics.at(id.index()); }

}  // namespace tsrir::diagnose
