#include "metrics/metrics_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "metrics/metric_columns.h"
#include "util/json.h"
#include "util/strings.h"

namespace tsrir {

namespace {

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return format_double(v);
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

void write_stats_json(JsonWriter& json, const ParameterStats& s) {
  json.field("mean", s.mean).field("std", s.std).field("median", s.median).field("count", s.count);
}

}  // namespace

MetricsSummary::MetricsSummary() : values_(metric_columns().size()) {}

void MetricsSummary::add(const RirMetrics& m) {
  ++num_rirs_;
  const auto& columns = metric_columns();
  for (size_t c = 0; c < columns.size(); ++c) {
    const double v = m.*columns[c].value;
    if (std::isfinite(v)) values_[c].push_back(v);
  }
}

ParameterStats MetricsSummary::stats(const std::string& name) const { return stats(metric_column_index(name)); }

ParameterStats MetricsSummary::stats(size_t column) const {
  ParameterStats s;
  std::vector<double> v = values_.at(column);
  s.count = v.size();
  if (v.empty()) return s;
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / (double)v.size();
  if (v.size() > 1) {
    double ss = 0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(ss / (double)(v.size() - 1));
  }
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  s.median = v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
  return s;
}

void write_summary_json(JsonWriter& json, const MetricsSummary& summary) {
  json.begin_object();
  json.field("count", summary.num_rirs());
  for (size_t c : summary_columns()) {
    json.key(metric_columns()[c].json_key).begin_object();
    write_stats_json(json, summary.stats(c));
    json.end_object();
  }
  json.end_object();
}

int closest_set(const NamedSummary& reference, const std::vector<NamedSummary>& sets, size_t column) {
  const double ref = reference.summary.stats(column).mean;
  int best = -1;
  double best_diff = INFINITY;
  for (size_t i = 0; i < sets.size(); ++i) {
    const double d = std::abs(sets[i].summary.stats(column).mean - ref);
    if (std::isfinite(d) && d < best_diff) {
      best_diff = d;
      best = (int)i;
    }
  }
  return best;
}

void write_reference_table(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                           const std::string& definition) {
  size_t name_width = reference.name.size();
  for (const auto& s : sets) name_width = std::max(name_width, s.name.size());
  name_width = std::max<size_t>(name_width, 3) + 2;
  constexpr int kCell = 20;
  out << "# Mean acoustic parameters per RIR set (definition " << definition
      << "); (|mean - reference mean|); * = closest to the reference\n";
  out << std::left << std::setw((int)name_width) << "# set" << std::setw(8) << "n";
  const std::vector<size_t>& columns = paper_table_columns();
  for (size_t c : columns) {
    out << std::setw(kCell) << (std::string(metric_columns()[c].name) + " (" + metric_columns()[c].unit + ")");
  }
  out << "\n";
  out << std::setw((int)name_width) << reference.name << std::setw(8) << reference.summary.num_rirs();
  for (size_t c : columns) {
    out << std::setw(kCell) << fixed(reference.summary.stats(c).mean, metric_columns()[c].summary_decimals);
  }
  out << "(reference)\n";
  std::vector<int> closest;
  for (size_t c : columns) closest.push_back(closest_set(reference, sets, c));
  for (size_t i = 0; i < sets.size(); ++i) {
    out << std::setw((int)name_width) << sets[i].name << std::setw(8) << sets[i].summary.num_rirs();
    for (size_t k = 0; k < columns.size(); ++k) {
      const size_t c = columns[k];
      const int decimals = metric_columns()[c].summary_decimals;
      const double mean = sets[i].summary.stats(c).mean;
      const double diff = std::abs(mean - reference.summary.stats(c).mean);
      std::string cell = fixed(mean, decimals) + " (" + fixed(diff, decimals) + ")";
      if (closest[k] == (int)i) cell += "*";
      out << std::setw(kCell) << cell;
    }
    out << "\n";
  }
  out << std::right;
}

void write_reference_json(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                          const std::string& definition) {
  JsonWriter json(out);
  json.begin_object();
  json.field("definition", definition);
  json.key("reference").begin_object();
  json.field("name", reference.name).field("count", reference.summary.num_rirs());
  for (size_t c : summary_columns()) {
    json.key(metric_columns()[c].json_key).begin_object();
    write_stats_json(json, reference.summary.stats(c));
    json.end_object();
  }
  json.end_object();
  json.key("sets").begin_array();
  for (size_t i = 0; i < sets.size(); ++i) {
    json.begin_object();
    json.field("name", sets[i].name).field("count", sets[i].summary.num_rirs());
    for (size_t c : summary_columns()) {
      const ParameterStats s = sets[i].summary.stats(c);
      json.key(metric_columns()[c].json_key).begin_object();
      write_stats_json(json, s);
      json.field("diff", std::abs(s.mean - reference.summary.stats(c).mean));
      json.field("closest", closest_set(reference, sets, c) == (int)i);
      json.end_object();
    }
    json.end_object();
  }
  json.end_array();
  json.end_object();
  out << "\n";
}

}  // namespace tsrir
