// The single-number acoustic parameters of an RIR, each declared once: name, unit, definition under
// each convention (rir-metrics --definition), JSON key, output formats and whether it is a column of
// the TS-RIR paper's Table 1. The per-RIR table and JSON (metrics_report.h), the set statistics and
// Table 1 (metrics_summary.h) and rir-metrics --help iterate this table. Adding a parameter = one
// RirMetrics field, one entry in metric_columns.cc, and its computation in measure_rir (both
// definitions).
#pragma once
#include <string>
#include <vector>

#include "metrics/rir_metrics.h"

namespace tsrir {

struct MetricColumn {
  const char* name;                // table header and Table-1 column, e.g. "T60"
  const char* unit;                // "s", "dB", "%"
  const char* json_key;            // key in the per-RIR and summary JSON
  const char* iso_definition;      // --definition=iso
  const char* irstats_definition;  // --definition=irstats
  int table_digits;                // significant digits in the per-RIR table (format_double)
  int summary_decimals;            // fixed decimals in Table 1
  int paper_table_position;        // column in the paper's Table 1 (0-based); -1: not in it
  double RirMetrics::*value;
};

// In per-RIR output order.
const std::vector<MetricColumn>& metric_columns();
// Index in metric_columns() of the column named `name`; throws Error for an unknown name.
size_t metric_column_index(const std::string& name);
// The paper's Table 1 columns (T60, DRR, EDT, C50), in its order, as metric_columns() indices.
const std::vector<size_t>& paper_table_columns();
// Set-statistics order: the paper's columns first, then the others in declaration order.
const std::vector<size_t>& summary_columns();
// "  T60  (s)   <definition under `definition`>" lines for --help.
std::string metric_columns_help(MetricsDefinition definition);

}  // namespace tsrir
