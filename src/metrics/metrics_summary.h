// Set-level statistics of RIR metrics and the TS-RIR paper's Table 1 (mean per set, |mean - the
// reference set's mean|, closest set per column).
#pragma once
#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "metrics/rir_metrics.h"

namespace tsrir {

class JsonWriter;

// Statistics per single-number parameter: `column` indexes metric_columns() (metric_columns.h).

struct ParameterStats {
  size_t count = 0;         // finite values only; NaNs (unmeasurable) are left out
  double mean = kMetricsNaN;
  double std = kMetricsNaN; // sample standard deviation (n - 1); NaN below 2 values
  double median = kMetricsNaN;
};

// Accumulates one value per parameter and RIR (a few doubles per RIR, so sets of millions fit).
class MetricsSummary {
 public:
  MetricsSummary();
  void add(const RirMetrics& m);
  size_t num_rirs() const { return num_rirs_; }
  ParameterStats stats(size_t column) const;
  ParameterStats stats(const std::string& name) const;  // by column name, e.g. "T60"

 private:
  size_t num_rirs_ = 0;
  std::vector<std::vector<double>> values_;  // per column
};

void write_summary_json(JsonWriter& json, const MetricsSummary& summary);

struct NamedSummary {
  std::string name;
  MetricsSummary summary;
};

// Table 1 as text: the paper's columns (T60, DRR, EDT, C50), one row per set (the reference first),
// "mean (|diff|)" cells, '*' on the set closest to the reference in each column. The JSON carries
// every column of metric_columns().
void write_reference_table(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                           const std::string& definition);
void write_reference_json(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                          const std::string& definition);

// Index of the set with the smallest |mean - reference mean| for the column, or -1 if none is finite.
int closest_set(const NamedSummary& reference, const std::vector<NamedSummary>& sets, size_t column);

}  // namespace tsrir
