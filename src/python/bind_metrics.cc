// metrics(): measure_rir() on one RIR, reported through rir-metrics' own JSON report, so the keys
// and values are exactly those of `rir-metrics --format=json` (the Python side parses the row).
#include <sstream>

#include "arrays.h"
#include "bindings.h"
#include "metrics/metrics_report.h"
#include "metrics/rir_metrics.h"

namespace tsrir::python {

void bind_metrics(py::module_& m) {
  const MetricsOptions defaults;  // the programs' defaults
  m.def(
      "metrics_json",
      [](const py::handle& rir, double fs, const std::string& definition, bool lundeby, double direct_pre_ms,
         double direct_post_ms, double clarity_ms, double onset_db, const std::string& rir_id) {
        Signal signal;
        signal.id = rir_id;
        signal.sample_rate_hz = fs;
        signal.samples = to_samples(rir, "rir");
        MetricsOptions options;
        options.definition = parse_metrics_definition(definition);
        options.lundeby = lundeby;
        options.direct_pre_ms = direct_pre_ms;
        options.direct_post_ms = direct_post_ms;
        options.clarity_time_ms = clarity_ms;
        options.onset_threshold_db = onset_db;
        std::ostringstream json;
        {
          py::gil_scoped_release release;
          const RirMetrics measured = measure_rir(signal, options);
          MetricsReport report(json, MetricsFormat::kJson, true);
          report.add(measured);
          report.finish();
        }
        return json.str();
      },
      py::arg("rir"), py::arg("fs"), py::arg("definition") = "iso", py::arg("lundeby") = defaults.lundeby,
      py::arg("direct_pre_ms") = defaults.direct_pre_ms,
      py::arg("direct_post_ms") = defaults.direct_post_ms, py::arg("clarity_ms") = defaults.clarity_time_ms,
      py::arg("onset_db") = defaults.onset_threshold_db, py::arg("rir_id") = "rir",
      "rir-metrics --format=json for one RIR (the whole document, as text).");
  m.def(
      "rir_onset_index",
      [](const py::handle& rir, double fs, double onset_db) {
        Signal signal;
        signal.sample_rate_hz = fs;
        signal.samples = to_samples(rir, "rir");
        MetricsOptions options;
        options.onset_threshold_db = onset_db;
        py::gil_scoped_release release;
        return measure_rir(signal, options).onset_sample;
      },
      py::arg("rir"), py::arg("fs"), py::arg("onset_db") = defaults.onset_threshold_db,
      "The direct sound's arrival as rir-metrics (iso) finds it: the first sample whose energy is\n"
      "within onset_db of the peak's (ISO 3382-1). Unlike the largest sample (rir_shift_index), a\n"
      "reflection stronger than the direct sound does not move it.");
}

}  // namespace tsrir::python
