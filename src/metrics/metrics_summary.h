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

// The four single-number parameters, in the paper's Table 1 column order.
enum class SetParameter { kT60 = 0, kDrr = 1, kEdt = 2, kC50 = 3 };
constexpr int kNumSetParameters = 4;
const char* set_parameter_name(SetParameter p);   // "T60", "DRR", "EDT", "C50"
const char* set_parameter_unit(SetParameter p);   // "s" | "dB"
double set_parameter_value(const RirMetrics& m, SetParameter p);

struct ParameterStats {
  size_t count = 0;         // finite values only; NaNs (unmeasurable) are left out
  double mean = kMetricsNaN;
  double std = kMetricsNaN; // sample standard deviation (n - 1); NaN below 2 values
  double median = kMetricsNaN;
};

// Accumulates one value per parameter and RIR (4 doubles per RIR, so sets of millions fit).
class MetricsSummary {
 public:
  void add(const RirMetrics& m);
  size_t num_rirs() const { return num_rirs_; }
  ParameterStats stats(SetParameter p) const;

 private:
  size_t num_rirs_ = 0;
  std::array<std::vector<double>, kNumSetParameters> values_;
};

void write_summary_json(JsonWriter& json, const MetricsSummary& summary);

struct NamedSummary {
  std::string name;
  MetricsSummary summary;
};

// Table 1 as text: one row per set (the reference first), "mean (|diff|)" cells, '*' on the set
// closest to the reference in each column.
void write_reference_table(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                           const std::string& definition);
void write_reference_json(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                          const std::string& definition);

// Index of the set with the smallest |mean - reference mean| for p, or -1 if none is finite.
int closest_set(const NamedSummary& reference, const std::vector<NamedSummary>& sets, SetParameter p);

}  // namespace tsrir
