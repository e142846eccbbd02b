#include "metrics/metric_columns.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "util/error.h"

namespace tsrir {

const std::vector<MetricColumn>& metric_columns() {
  static const std::vector<MetricColumn> columns = {
      {"T60", "s", "T60",
       "mean T30 of the 500 Hz and 1 kHz octave bands (T20 where the dynamic range is too small)",
       "mean of the 500 Hz and 1 kHz octave bands' direct 0..-60 dB decay fits", 6, 4, 0, &RirMetrics::t60_s},
      {"EDT", "s", "EDT", "mean early decay time (0..-10 dB, x6) of the 500 Hz and 1 kHz octave bands",
       "mean 0..-10 dB decay fit (x6) of the 500 Hz and 1 kHz octave bands", 6, 4, 2, &RirMetrics::edt_s},
      {"DRR", "dB", "DRR",
       "direct energy in [peak - --direct-pre-ms, peak + --direct-post-ms] over the (noise-compensated) rest",
       "direct energy in peak +-2.5 ms over the rest (trapezoidal sums)", 6, 4, 1, &RirMetrics::drr_db},
      {"C50", "dB", "C50",
       "clarity: energy in the first --clarity-ms (50) ms from the onset over the (noise-compensated) rest",
       "the paper's CTE: energy from 2.5 ms before the peak to --clarity-ms (50) ms after it over the rest", 6, 4, 3,
       &RirMetrics::c50_db},
      {"D50", "%", "D50",
       "definition (ISO 3382-1): energy in the first 50 ms from the onset over all energy from the onset, in %",
       "energy from 2.5 ms before the peak to 50 ms after it over all energy from 2.5 ms before the peak, in %", 6,
       4, -1, &RirMetrics::d50_percent},
      {"C80", "dB", "C80",
       "clarity for music (ISO 3382-1): energy in the first 80 ms from the onset over the (noise-compensated) rest",
       "energy from 2.5 ms before the peak to 80 ms after it over the rest (CTE with an 80 ms limit)", 6, 4, -1,
       &RirMetrics::c80_db},
  };
  return columns;
}

size_t metric_column_index(const std::string& name) {
  const auto& columns = metric_columns();
  for (size_t i = 0; i < columns.size(); ++i) {
    if (name == columns[i].name) return i;
  }
  throw Error("unknown acoustic parameter '" + name + "'");
}

const std::vector<size_t>& paper_table_columns() {
  static const std::vector<size_t> order = [] {
    std::vector<size_t> out;
    const auto& columns = metric_columns();
    for (size_t i = 0; i < columns.size(); ++i) {
      if (columns[i].paper_table_position >= 0) out.push_back(i);
    }
    std::sort(out.begin(), out.end(), [&](size_t a, size_t b) {
      return columns[a].paper_table_position < columns[b].paper_table_position;
    });
    return out;
  }();
  return order;
}

const std::vector<size_t>& summary_columns() {
  static const std::vector<size_t> order = [] {
    std::vector<size_t> out = paper_table_columns();
    for (size_t i = 0; i < metric_columns().size(); ++i) {
      if (metric_columns()[i].paper_table_position < 0) out.push_back(i);
    }
    return out;
  }();
  return order;
}

std::string metric_columns_help(MetricsDefinition definition) {
  std::ostringstream os;
  for (const MetricColumn& c : metric_columns()) {
    os << "  " << std::left << std::setw(4) << c.name << std::setw(5) << (std::string("(") + c.unit + ")")
       << (definition == MetricsDefinition::kIso ? c.iso_definition : c.irstats_definition) << "\n";
  }
  return os.str();
}

}  // namespace tsrir
