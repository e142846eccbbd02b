// Per-RIR output of rir-metrics: a whitespace table ('#' header) or JSON, written row by row so
// sets of any size stream through in input order.
#pragma once
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "metrics/metrics_summary.h"
#include "metrics/rir_metrics.h"

namespace tsrir {

class JsonWriter;

enum class MetricsFormat { kTable, kJson };
const Choices<MetricsFormat>& metrics_format_choices();       // "table" | "json"
MetricsFormat parse_metrics_format(const std::string& name);

// Band column label: "62.5", "125", ..., "8000".
std::string band_label(double center_hz);

class MetricsReport {
 public:
  // with_bands: per-band T20/T30/EDT columns (table) -- JSON always carries the bands.
  MetricsReport(std::ostream& out, MetricsFormat format, bool with_bands);
  ~MetricsReport();
  // Rows in the order they are added. The table header is written with the first row; its band
  // columns are that RIR's bands (a set normally has one rate), other bands print as nan.
  // in_summary false: a row printed but left out of the set statistics (an array's mean row).
  void add(const RirMetrics& m, bool in_summary = true);
  // An RIR skipped with --skip-errors (kept in the JSON "errors" list).
  void add_error(const std::string& id, const std::string& message);
  // Writes the JSON summary (table: nothing more) and closes the document.
  void finish();
  const MetricsSummary& summary() const { return summary_; }

 private:
  std::ostream& out_;
  MetricsFormat format_;
  bool with_bands_;
  bool header_written_ = false;
  std::vector<double> columns_;
  std::unique_ptr<JsonWriter> json_;
  std::vector<std::pair<std::string, std::string>> errors_;
  MetricsSummary summary_;
};

}  // namespace tsrir
