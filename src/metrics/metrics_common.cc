#include "metrics/metrics_common.h"

#include <cmath>
#include <map>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir::metrics_detail {

std::string band_name(double center_hz) { return center_hz > 0 ? format_double(center_hz) + " Hz" : "broadband"; }

std::string rir_name(const Signal& rir) { return "RIR '" + rir.id + "'"; }

RirMetrics metrics_of(const Signal& rir) {
  RirMetrics m;
  m.id = rir.id;
  m.sample_rate_hz = rir.sample_rate_hz;
  return m;
}

// Errors name the RIR: no samples, NaN or Inf, silence, a rate that is not positive.
void validate(const Signal& rir) {
  if (!(rir.sample_rate_hz > 0)) throw Error(rir_name(rir) + ": sample rate must be positive");
  if (rir.samples.empty()) throw Error(rir_name(rir) + ": no samples");
  bool any = false;
  for (size_t i = 0; i < rir.samples.size(); ++i) {
    const float v = rir.samples[i];
    if (!std::isfinite(v)) throw Error(rir_name(rir) + ": NaN or Inf at sample " + std::to_string(i));
    any = any || v != 0.0f;
  }
  if (!any) throw Error(rir_name(rir) + ": silent (all samples are zero)");
}

// Filters for one (rate, definition), designed once per thread: designs cost microseconds each
// but RIR sets usually share one rate.
const std::vector<SosFilter>& band_filters(double fs, const std::vector<double>& centers) {
  thread_local std::map<std::pair<double, std::vector<double>>, std::vector<SosFilter>> cache;
  auto key = std::make_pair(fs, centers);
  auto it = cache.find(key);
  if (it == cache.end()) {
    std::vector<SosFilter> filters;
    for (double fc : centers) filters.push_back(ansi_octave_filter(fc, fs, kOctaveOrder));
    it = cache.emplace(std::move(key), std::move(filters)).first;
  }
  return it->second;
}

namespace {
double mean_of_mid_bands(const RirMetrics& m, double BandMetrics::*field) {
  const BandMetrics* a = m.band(500.0);
  const BandMetrics* b = m.band(1000.0);
  if (!a || !b) return kNaN;
  return 0.5 * (a->*field + b->*field);
}
}  // namespace

// The single-number values: mean of the 500 Hz and 1 kHz bands, NaN (with a reason) otherwise.
void set_mid_band_values(RirMetrics* m) {
  m->t60_s = mean_of_mid_bands(*m, &BandMetrics::rt_s);
  m->edt_s = mean_of_mid_bands(*m, &BandMetrics::edt_s);
  if (!m->band(500.0) || !m->band(1000.0)) {
    m->warnings.push_back("T60, EDT: the 500 Hz and 1 kHz bands are not both measured at " +
                          format_double(m->sample_rate_hz) + " Hz");
  } else {
    if (!std::isfinite(m->t60_s)) m->warnings.push_back("T60: unmeasurable in the 500 Hz or 1 kHz band");
    if (!std::isfinite(m->edt_s)) m->warnings.push_back("EDT: unmeasurable in the 500 Hz or 1 kHz band");
  }
}

double energy_sum(const std::vector<float>& h, size_t begin, size_t end) {
  double s = 0;
  for (size_t i = begin; i < end && i < h.size(); ++i) s += (double)h[i] * h[i];
  return s;
}

MetricsWorkspace& metrics_workspace() {
  thread_local MetricsWorkspace w;
  return w;
}

}  // namespace tsrir::metrics_detail
