// The parameters as IoSR irStats computes them (MetricsDefinition::kIrstats). Internal to
// src/metrics: rir_metrics.h's measure_rir checks the RIR and calls this.
#pragma once
#include "metrics/rir_metrics.h"

namespace tsrir::metrics_detail {

// A checked RIR (non-empty, finite, not silent, positive rate).
RirMetrics measure_irstats(const Signal& rir, const MetricsOptions& options);

}  // namespace tsrir::metrics_detail
