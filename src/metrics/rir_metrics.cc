#include "metrics/rir_metrics.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "dsp/bands.h"
#include "dsp/octave_filter.h"
#include "metrics/decay_fit.h"
#include "metrics/irstats.h"
#include "metrics/metrics_common.h"
#include "metrics/metrics_irstats.h"
#include "metrics/metrics_iso.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

using metrics_detail::kOctaveOrder;

const Choices<MetricsDefinition>& metrics_definition_choices() {
  static const Choices<MetricsDefinition> choices = {{"iso", MetricsDefinition::kIso},
                                                     {"irstats", MetricsDefinition::kIrstats}};
  return choices;
}

MetricsDefinition parse_metrics_definition(const std::string& name) {
  return parse_choice(metrics_definition_choices(), name, "metrics definition");
}

void MetricsOptions::Register(OptionsItf* opts) {
  opts->RegisterEnum("definition", &definition, metrics_definition_choices(), "definition of the parameters");
  opts->Register("lundeby", &lundeby, "iso: noise-floor subtraction, Lundeby truncation and compensation");
  opts->Register("direct-pre-ms", &direct_pre_ms, "iso: direct-sound window before the peak (ms)");
  opts->Register("direct-post-ms", &direct_post_ms, "iso: direct-sound window after the peak (ms)");
  opts->Register("clarity-ms", &clarity_time_ms, "early/late limit of the clarity index (ms)");
  opts->Register("onset-db", &onset_threshold_db, "iso: onset = first sample within this many dB of the peak");
}

std::string metrics_definition_name(MetricsDefinition definition) {
  return choice_name(metrics_definition_choices(), definition);
}

const BandMetrics* RirMetrics::band(double center_hz) const {
  for (const BandMetrics& b : bands)
    if (b.center_hz == center_hz) return &b;
  return nullptr;
}

std::vector<double> metrics_band_centers_hz(double fs, MetricsDefinition definition) {
  if (definition == MetricsDefinition::kIrstats) return irstats_band_centers_hz(fs);
  std::vector<double> out;
  for (double fc : kOctaveCentersHz) {
    if (ansi_octave_edges_hz(fc, kOctaveOrder).high_hz < fs / 2) out.push_back(fc);
  }
  return out;
}

std::vector<double> schroeder_decay_db(const std::vector<float>& h, size_t begin, size_t end) {
  end = std::min(end, h.size());
  if (begin >= end) return {};
  std::vector<double> e(end - begin);
  for (size_t i = begin; i < end; ++i) e[i - begin] = (double)h[i] * h[i];
  std::vector<double> edc = backward_integral(e.data(), e.size());
  const double ref = edc[0];
  for (double& v : edc) v = ref > 0 ? 10.0 * std::log10(v / ref) : -INFINITY;
  return edc;
}

RirMetrics measure_rir(const Signal& rir, const MetricsOptions& options) {
  using metrics_detail::measure_irstats;
  using metrics_detail::measure_iso;
  metrics_detail::validate(rir);
  return options.definition == MetricsDefinition::kIso ? measure_iso(rir, options) : measure_irstats(rir, options);
}

}  // namespace tsrir
