// The parameters by ISO 3382-1 (MetricsDefinition::kIso). Internal to src/metrics: rir_metrics.h's
// measure_rir checks the RIR and calls this.
#pragma once
#include "metrics/rir_metrics.h"

namespace tsrir::metrics_detail {

// A checked RIR (non-empty, finite, not silent, positive rate).
RirMetrics measure_iso(const Signal& rir, const MetricsOptions& options);

}  // namespace tsrir::metrics_detail
