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
  // Every channel of a multichannel RIR (a microphone array's) measured on its own: rows
  // <id>-ch<c> (c = 0, 1, ...) and <id>-mean (channel_mean()); exclusive with channel != 0.
  bool all_channels = false;
  int num_threads = 1;
  bool skip_errors = false;   // report failing RIRs and go on; default: stop at the first
  size_t chunk_size = 0;      // RIRs in flight at once; 0 = 32 per thread

  // metrics' options, --channel, --all-channels, --num-threads, --skip-errors
  void Register(OptionsItf* opts);
};

struct MetricsOutcome {
  std::string id;
  bool ok = false;
  RirMetrics metrics;         // with all_channels: the channels' mean (channel_mean)
  std::vector<RirMetrics> channels;  // with all_channels: one per channel, ids <id>-ch<c>
  std::string error;          // names the RIR id (and where it was listed)
};

// The array's mean row, id `id`: every single number of metric_columns() and every band value the
// mean of the channels' (NaN where a channel's is NaN: an unmeasurable channel is not hidden),
// the broadband decay the same, warnings of every channel prefixed by its id.
RirMetrics channel_mean(const std::vector<RirMetrics>& channels, const std::string& id);

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
