#include "metrics/metrics_report.h"

#include <cmath>

#include "metrics/metric_columns.h"
#include "util/error.h"
#include "util/json.h"
#include "util/strings.h"

namespace tsrir {

const Choices<MetricsFormat>& metrics_format_choices() {
  static const Choices<MetricsFormat> choices = {{"table", MetricsFormat::kTable}, {"json", MetricsFormat::kJson}};
  return choices;
}

MetricsFormat parse_metrics_format(const std::string& name) {
  return parse_choice(metrics_format_choices(), name, "format");
}

std::string band_label(double center_hz) { return format_double(center_hz, 6); }

MetricsReport::MetricsReport(std::ostream& out, MetricsFormat format, bool with_bands)
    : out_(out), format_(format), with_bands_(with_bands) {
  if (format_ == MetricsFormat::kJson) {
    json_ = std::make_unique<JsonWriter>(out_);
    json_->begin_object();
    json_->key("rirs").begin_array();
  }
}

MetricsReport::~MetricsReport() = default;

void MetricsReport::add(const RirMetrics& m, bool in_summary) {
  if (in_summary) summary_.add(m);
  if (format_ == MetricsFormat::kTable) {
    if (!header_written_) {
      out_ << "# id";
      for (const MetricColumn& c : metric_columns()) out_ << ' ' << c.name;
      if (with_bands_) {
        for (const BandMetrics& b : m.bands) {
          columns_.push_back(b.center_hz);
          const std::string l = band_label(b.center_hz);
          out_ << " T20_" << l << " T30_" << l << " EDT_" << l;
        }
      }
      out_ << "\n";
      header_written_ = true;
    }
    out_ << m.id;
    for (const MetricColumn& c : metric_columns()) out_ << ' ' << format_double(m.*c.value, c.table_digits);
    for (double fc : columns_) {
      const BandMetrics* b = m.band(fc);
      out_ << ' ' << format_double(b ? b->t20_s : kMetricsNaN) << ' ' << format_double(b ? b->t30_s : kMetricsNaN)
           << ' ' << format_double(b ? b->edt_s : kMetricsNaN);
    }
    out_ << "\n";
    return;
  }
  JsonWriter& j = *json_;
  j.begin_object();
  j.field("id", m.id);
  for (const MetricColumn& c : metric_columns()) j.field(c.json_key, m.*c.value);
  j.key("bands").begin_object();
  for (const BandMetrics& b : m.bands) {
    j.key(band_label(b.center_hz)).begin_object();
    j.field("T20", b.t20_s).field("T30", b.t30_s).field("EDT", b.edt_s).field("RT", b.rt_s).field("level", b.level_db);
    j.end_object();
  }
  j.end_object();
  j.key("broadband").begin_object();
  j.field("T20", m.broadband.t20_s).field("T30", m.broadband.t30_s).field("EDT", m.broadband.edt_s);
  j.end_object();
  j.key("warnings").begin_array();
  for (const std::string& w : m.warnings) j.value(w);
  j.end_array();
  j.end_object();
}

void MetricsReport::add_error(const std::string& id, const std::string& message) {
  errors_.emplace_back(id, message);
}

void MetricsReport::finish() {
  if (format_ == MetricsFormat::kTable) {
    out_.flush();
    return;
  }
  JsonWriter& j = *json_;
  j.end_array();
  j.key("summary");
  write_summary_json(j, summary_);
  j.key("errors").begin_array();
  for (const auto& e : errors_) {
    j.begin_object();
    j.field("id", e.first).field("error", e.second);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  out_ << "\n";
  out_.flush();
}

}  // namespace tsrir
