// The rir-metrics program body: streams RIR sets through measure_rir on several threads, in
// chunks, writing rows in input order; or, with a reference set, prints the paper's Table 1.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "io/rir_set.h"
#include "metrics/metrics_report.h"
#include "metrics/rir_metrics.h"

namespace tsrir {

struct MetricsRunOptions {
  MetricsOptions metrics;
  int channel = 0;            // -1 = mean of all channels
  int num_threads = 1;
  bool skip_errors = false;   // report failing RIRs and go on; default: stop at the first
  size_t chunk_size = 0;      // RIRs in flight at once; 0 = 32 per thread

  void Register(OptionsItf* opts);  // metrics' options, --channel, --num-threads, --skip-errors
};

struct MetricsOutcome {
  std::string id;
  bool ok = false;
  RirMetrics metrics;
  std::string error;          // names the RIR id (and where it was listed)
};

// Loads and measures every ref; on_result sees them in input order. Without skip_errors the first
// failing RIR (in input order) is rethrown as Error after the ones before it were delivered.
void measure_rir_refs(const std::vector<RirRef>& refs, const MetricsRunOptions& options,
                      const std::function<void(const MetricsOutcome&)>& on_result);

struct RirMetricsCommand {
  MetricsRunOptions run;
  MetricsFormat format = MetricsFormat::kTable;
  bool bands = false;
  std::string reference;      // non-empty: Table-1 mode against this set
  std::string output = "-";
  std::vector<std::string> inputs;  // positional: not registered

  void Register(OptionsItf* opts);
};

// Returns the exit status (0: success; 1: some RIRs were skipped and none succeeded).
int run_rir_metrics(const RirMetricsCommand& command);

}  // namespace tsrir
