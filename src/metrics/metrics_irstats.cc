// IoSR irStats parameters as used for the TS-RIR paper's Table 1 (MetricsDefinition::kIrstats):
// peak as t0, causal Butterworth octaves, direct 0..-60 dB fit, DRR +-2.5 ms, CTE from -2.5 ms.
#include "metrics/metrics_irstats.h"

#include <cmath>

#include "metrics/irstats.h"
#include "metrics/metrics_common.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir::metrics_detail {
namespace {

// D50 and C80 the way irStats computes its CTE: early energy from 2.5 ms before the peak to the
// limit, late energy after it, trapezoidal sums (irstats.h).
void irstats_d50_c80(const std::vector<float>& x, size_t t0, double fs, RirMetrics* m) {
  const size_t n = x.size();
  const size_t c = (size_t)std::lround(0.0025 * fs);
  const size_t begin = t0 >= c ? t0 - c : 0;
  const size_t te50 = (size_t)std::lround(0.050 * fs), te80 = (size_t)std::lround(0.080 * fs);
  if (t0 + te50 + 1 < n) {
    const double early = irstats_trapz_energy(x, begin, t0 + te50);
    const double all = early + irstats_trapz_energy(x, t0 + te50 + 1, n - 1);
    m->d50_percent = all > 0 ? 100.0 * early / all : kNaN;
  } else {
    m->warnings.push_back("D50: early time limit (50 ms) out of range");
  }
  if (t0 + te80 + 1 < n) {
    m->c80_db = 10.0 * std::log10(irstats_trapz_energy(x, begin, t0 + te80) / irstats_trapz_energy(x, t0 + te80 + 1, n - 1));
  } else {
    m->warnings.push_back("C80: early time limit (80 ms) out of range");
  }
}

BandMetrics irstats_band(const double* z, size_t n, double center_hz, double fs, std::vector<std::string>* warnings) {
  BandMetrics b;
  b.center_hz = center_hz;
  const std::string label = band_name(center_hz);
  thread_local IrstatsDecayFitter fitter;
  fitter.reset(z, n);
  auto decay = [&](double hi, double lo, const char* what) {
    const IrstatsDecay d = fitter.fit(fs, hi, lo);
    if (!d.range_reached) {
      warnings->push_back(label + ": " + what + ": decay never reaches " + format_double(lo) +
                          " dB; fit ends at the last sample (irStats behaviour)");
    }
    if (!d.failure.empty()) warnings->push_back(label + ": " + what + ": " + d.failure);
    return d.time_s;
  };
  b.rt_s = decay(0.0, -60.0, "RT");
  b.edt_s = decay(0.0, -10.0, "EDT");
  b.t20_s = decay(-5.0, -25.0, "T20");
  b.t30_s = decay(-5.0, -35.0, "T30");
  return b;
}

}  // namespace

RirMetrics measure_irstats(const Signal& rir, const MetricsOptions& o) {
  const double fs = rir.sample_rate_hz;
  if (fs < 5000) throw Error(rir_name(rir) + ": irstats needs a sample rate of at least 5000 Hz");
  RirMetrics m = metrics_of(rir);
  const std::vector<float>& x = rir.samples;
  const size_t n = x.size();
  const size_t te = (size_t)std::lround(o.clarity_time_ms * 1e-3 * fs);
  if (te >= n) {
    throw Error(rir_name(rir) + ": too short: " + format_double(1e3 * n / fs, 4) + " ms, the early time limit is " +
                format_double(o.clarity_time_ms) + " ms");
  }
  size_t ties = 0;
  const size_t t0 = irstats_peak_index(x, &ties);
  if (ties > 1) m.warnings.push_back("more than one peak found; choosing the first (irStats behaviour)");
  m.onset_sample = m.peak_sample = t0;

  const IrstatsRatios ratios = irstats_drr_cte(x, t0, fs, 0.0025, o.clarity_time_ms * 1e-3);
  m.drr_db = ratios.drr_db;
  m.c50_db = ratios.cte_db;
  m.warnings.insert(m.warnings.end(), ratios.warnings.begin(), ratios.warnings.end());
  irstats_d50_c80(x, t0, fs, &m);

  MetricsWorkspace& w = metrics_workspace();
  w.energy.assign(x.begin(), x.end());
  irstats_decay_curve(w.energy.data(), n, &w.tail);
  m.broadband = irstats_band(w.tail.data() + t0, n - t0, 0.0, fs, &m.warnings);
  m.broadband.level_db = 0.0;

  const std::vector<double> centers = metrics_band_centers_hz(fs, MetricsDefinition::kIrstats);
  std::vector<std::vector<double>>& y = w.bands;
  sos_filter_bank(band_filters(fs, centers), x.data(), n, /*time_reversed=*/false, &y);
  const double total = energy_sum(x, 0, n);
  for (size_t b = 0; b < centers.size(); ++b) {
    irstats_decay_curve(y[b].data(), n, &w.tail);
    BandMetrics bm = irstats_band(w.tail.data() + t0, n - t0, centers[b], fs, &m.warnings);
    double band_total = 0;
    for (double v : y[b]) band_total += v * v;
    bm.level_db = band_total > 0 ? 10.0 * std::log10(band_total / total) : -INFINITY;
    m.bands.push_back(bm);
  }
  set_mid_band_values(&m);
  return m;
}

}  // namespace tsrir::metrics_detail
