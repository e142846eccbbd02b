// The metrics rir-diagnose judges its models with on the held-out RIRs (the gain table): its own
// comparisons (per-band decay and level, the low-frequency spectrum, onsets, the tail, the early
// echo density, the late-field persistence) and every single-number parameter of the metric
// table (src/metrics/metric_columns.cc: T60, EDT, DRR, C50, D50, C80, ...), so that a parameter
// added there is a gain metric here with no other edit. Each metric is the per-RIR absolute
// error of a render against its measurement, over the span where the measurement is above its
// floor (tail metrics stop at its digital silence, decay metrics at its noise: rir_features.h).
// An effect names the metric its extension acts on by a typed id, checked when it is registered.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "diagnose/rir_features.h"

namespace tsrir::diagnose {

// rir-diagnose's own metrics (the metric table's columns are addressed by their table name).
enum class OwnMetric { kT30PerBand, kLevelPerBand, kLfSpectralDistance, kLfPersistence, kOnset, kTailLevel, kEchoDensity };

class GainMetricId {
 public:
  static GainMetricId own(OwnMetric metric);
  // A column of the metric table by its name ("DRR", "C80"); throws Error for an unknown name.
  static GainMetricId column(const std::string& table_name);
  // The metric whose gain-table name is `name` ("drr", "t30_per_band"); throws Error for an unknown one.
  static GainMetricId named(const std::string& name);
  size_t index() const { return index_; }  // in gain_metrics()
  bool operator==(const GainMetricId& o) const { return index_ == o.index_; }
  bool operator!=(const GainMetricId& o) const { return index_ != o.index_; }

 private:
  explicit GainMetricId(size_t index) : index_(index) {}
  size_t index_;
};

struct GainMetric {
  std::string name;  // findings.json key: the own metrics' names, the table's columns in lower case ("drr")
  std::string unit;
  // The smallest change of the mean error worth reporting as a metric made worse (a just-noticeable
  // difference where one is known: ISO 3382-1 Annex A gives 1 dB for C80 and G, 5 % for D50 and
  // EDT); the metric table's columns take it from their unit (unit_jnd).
  double jnd = 0.0;
  // Per-RIR absolute error of a render's features against the measurement's; NaN where either
  // is not measured. Empty for the echo density, which is compared per pair of renders
  // (cross-equalised, diagnose.cc).
  std::function<double(const RirFeatures& measured, const RirFeatures& simulated)> error;
};

// The just-noticeable difference of a metric-table column by its unit: dB 1 (ISO 3382-1: C80, G),
// s 0.02 (5 % of a 0.4 s decay: EDT's), % 5 (D50's); 0 for any other unit (every significant change counts).
double unit_jnd(const std::string& unit);

// In gain-table order: per-band decay and level, the metric table's columns, then the others.
const std::vector<GainMetric>& gain_metrics();
const GainMetric& gain_metric(GainMetricId id);

}  // namespace tsrir::diagnose
