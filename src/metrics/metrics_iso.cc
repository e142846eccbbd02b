// ISO 3382-1 parameters (MetricsDefinition::kIso): onset 20 dB below the peak, Schroeder decay with
// noise subtraction, Lundeby truncation and compensation, octave bands filtered time-reversed.
#include "metrics/metrics_iso.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dsp/bands.h"
#include "metrics/decay_fit.h"
#include "metrics/lundeby.h"
#include "metrics/metrics_common.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir::metrics_detail {
namespace {

// A decay curve measured from the onset: noise power subtracted, truncated at the Lundeby
// intersection and compensated for the cut tail (or the plain Schroeder integral when noise
// handling is off).
struct IsoDecay {
  std::vector<double> edc;     // index 0 = onset
  size_t usable_end = 0;       // samples of edc that are measured (not extrapolated)
  size_t model_start = 0;      // where the modelled exponential tail takes over
  LundebyResult lundeby;
  double tail_energy = 0;
  bool truncated = false;
};

// The backward sums tail[i] = sum_{k>=i} energy[k] for i in [0, n] (tail[n] = 0), added from the
// end: the sum from any start s is the same numbers added in the same order, so one curve over
// the whole RIR serves every start.
void backward_sums(const double* energy, size_t n, std::vector<double>* tail) {
  tail->resize(n + 1);
  double* t = tail->data();
  t[n] = 0.0;
  for (size_t i = n; i-- > 0;) t[i] = t[i + 1] + energy[i];
}

// The same for several curves of one length at once: each sum is a chain of dependent additions
// (their latency, not the adds, bounds one curve); interleaved, the chains overlap. Each curve's
// additions and their order are those of backward_sums, so the values are the same to the bit.
void backward_sums_interleaved(const std::vector<std::vector<double>>& energies, size_t n,
                               std::vector<std::vector<double>>* tails) {
  const size_t count = energies.size();
  tails->resize(count);
  std::vector<const double*> e(count);
  std::vector<double*> t(count);
  for (size_t b = 0; b < count; ++b) {
    (*tails)[b].resize(n + 1);
    e[b] = energies[b].data();
    t[b] = (*tails)[b].data();
    t[b][n] = 0.0;
  }
  for (size_t i = n; i-- > 0;) {
    for (size_t b = 0; b < count; ++b) t[b][i] = t[b][i + 1] + e[b][i];
  }
}

// The first k in [0, end) with edc[k] <= 0 (or NaN), else `end`: blocks of 8 compared without an
// early exit (which vectorises), the block holding the first such value scanned one by one.
size_t first_not_positive(const double* edc, size_t end) {
  size_t k = 0;
  for (; k + 8 <= end; k += 8) {
    int bad = 0;
    for (size_t j = 0; j < 8; ++j) bad |= !(edc[k + j] > 0);
    if (bad) break;
  }
  while (k < end && edc[k] > 0) ++k;
  return k;
}

// `tail` = backward_sums of the n energies the decay starts with (tail[n] = 0).
void iso_decay(const double* tail, size_t n, double fs, double center_hz, bool use_lundeby, const std::string& label,
               std::vector<std::string>* warnings, IsoDecay* d) {
  d->lundeby = lundeby_intersection_from_tail(tail, n, fs, center_hz);
  d->tail_energy = 0;
  d->truncated = false;
  size_t end = n;
  if (use_lundeby) {
    if (d->lundeby.ok) {
      end = d->lundeby.intersection;
      d->tail_energy = lundeby_tail_energy(d->lundeby, fs);
      d->truncated = true;
    } else {
      warnings->push_back(label + ": noise-floor detection failed (" + d->lundeby.failure +
                          "); decay integrated without truncation");
    }
  }
  d->model_start = end;
  d->edc.resize(end);
  double* edc = d->edc.data();
  if (d->truncated) {
    // Chu: the noise is also present before the intersection; subtracting its power keeps it
    // from flattening the end of the evaluation range (T30 at 47 dB peak-to-noise: +2.9 % with
    // truncation and compensation alone, +1 % with the subtraction too).
    const double noise = d->lundeby.noise_power, cut = tail[end], tail_energy = d->tail_energy;
    if (end <= size_t(INT32_MAX)) {
      // The same values through 32-bit counts, whose conversion to double vectorises (SSE2).
      const int32_t end32 = int32_t(end);
      for (int32_t k = 0; k < end32; ++k) edc[k] = (tail[k] - cut) - noise * (double)(end32 - k) + tail_energy;
    } else {
      for (size_t k = 0; k < end; ++k) edc[k] = (tail[k] - cut) - noise * (double)(end - k) + tail_energy;
    }
    // Noise fluctuations can drive the last values to zero or below: those are not measured.
    end = first_not_positive(edc, end);
  } else {
    std::copy(tail, tail + end, edc);
  }
  d->usable_end = end;
}

// Each band's samples squared in place, with its energy (summed from the first sample on) and
// peak; the bands interleaved, as in backward_sums_interleaved, each sum in its own order.
void square_bands(std::vector<std::vector<double>>* bands, size_t n, std::vector<double>* total,
                  std::vector<double>* peak) {
  const size_t count = bands->size();
  total->assign(count, 0.0);
  peak->assign(count, 0.0);
  std::vector<double*> y(count);
  for (size_t b = 0; b < count; ++b) y[b] = (*bands)[b].data();
  double* sum = total->data();
  double* top = peak->data();
  for (size_t i = 0; i < n; ++i) {
    for (size_t b = 0; b < count; ++b) {
      const double v = y[b][i] * y[b][i];
      y[b][i] = v;
      sum[b] += v;
      top[b] = std::max(top[b], v);
    }
  }
}

// Energy from sample `k` (relative to the onset) to the end, noise-compensated: inside the
// measured part the EDC itself, beyond the intersection the modelled exponential tail.
double iso_late_energy(const IsoDecay& d, size_t k, double fs) {
  if (k < d.usable_end) return d.edc[k];
  if (!d.truncated || k < d.model_start) return 0.0;
  const double t_s = (double)(k - d.model_start) / fs;
  return d.tail_energy * std::pow(10.0, -6.0 * t_s / d.lundeby.late_decay_time_s);
}

// D50 and C80 (ISO 3382-1, fixed 50 and 80 ms limits): the early sums and the noise-compensated
// late energy of the broadband decay, as C50 uses them.
void iso_d50_c80(const std::vector<float>& h, size_t onset, double fs, const IsoDecay& bb, RirMetrics* m) {
  const size_t n = h.size();
  const size_t te50 = (size_t)std::lround(0.050 * fs), te80 = (size_t)std::lround(0.080 * fs);
  if (onset + te50 < n) {
    const double early = energy_sum(h, onset, onset + te50);
    const double all = early + iso_late_energy(bb, te50, fs);
    m->d50_percent = all > 0 ? 100.0 * early / all : kNaN;
  } else {
    m->warnings.push_back("D50: the RIR ends less than 50 ms after the onset");
  }
  if (onset + te80 < n) {
    const double early = energy_sum(h, onset, onset + te80);
    const double late = iso_late_energy(bb, te80, fs);
    m->c80_db = late > 0 ? 10.0 * std::log10(early / late) : kNaN;
    if (!(late > 0)) m->warnings.push_back("C80: no energy after 80 ms");
  } else {
    m->warnings.push_back("C80: the RIR ends less than 80 ms after the onset");
  }
}


BandMetrics iso_band_metrics(const IsoDecay& d, double center_hz, double fs, bool use_lundeby,
                             const std::string& label, std::vector<std::string>* warnings, std::vector<double>* db) {
  BandMetrics b;
  b.center_hz = center_hz;
  if (d.usable_end == 0 || !(d.edc[0] > 0)) {
    warnings->push_back(label + ": no energy after the onset");
    return b;
  }
  const double psnr = d.lundeby.peak_to_noise_db;
  if (use_lundeby && d.truncated) b.dynamic_range_db = psnr;
  // One dB conversion covers all three ranges (0 .. -35 dB).
  const size_t span = std::min(d.usable_end, first_index_at_or_below(d.edc.data(), d.usable_end, d.edc[0] * std::pow(10.0, -3.5)) + 1);
  db->resize(span);
  energy_to_db(d.edc.data(), span, db->data());
  // ISO 3382-1: the bottom of an evaluation range must lie >= 10 dB above the noise, so T30 needs
  // 45 dB and T20 35 dB of peak-to-noise ratio, EDT 20 dB.
  auto fit = [&](double upper_db, double lower_db) -> double {
    if (std::isfinite(psnr) && psnr < -lower_db + 10.0) return kNaN;
    return fit_decay_range(d.edc.data(), db->data(), d.usable_end, d.edc[0], fs, upper_db, lower_db).decay_time_s();
  };
  b.edt_s = fit(0.0, -10.0);
  b.t20_s = fit(-5.0, -25.0);
  b.t30_s = fit(-5.0, -35.0);
  const std::string range = std::isfinite(psnr) ? " (peak-to-noise " + format_double(psnr, 3) + " dB)" : "";
  if (std::isfinite(b.t30_s)) {
    b.rt_s = b.t30_s;
  } else if (std::isfinite(b.t20_s)) {
    b.rt_s = b.t20_s;
    warnings->push_back(label + ": dynamic range too small for T30" + range + "; reporting T20");
  } else {
    warnings->push_back(label + ": dynamic range too small for T20 and T30" + range);
  }
  if (!std::isfinite(b.edt_s)) warnings->push_back(label + ": dynamic range too small for EDT" + range);
  return b;
}

}  // namespace

RirMetrics measure_iso(const Signal& rir, const MetricsOptions& o) {
  RirMetrics m = metrics_of(rir);
  const std::vector<float>& h = rir.samples;
  const size_t n = h.size();
  const double fs = rir.sample_rate_hz;

  double peak_e = -1;
  for (size_t i = 0; i < n; ++i) {
    const double e = (double)h[i] * h[i];
    if (e > peak_e) {
      peak_e = e;
      m.peak_sample = i;
    }
  }
  const double onset_level = peak_e * std::pow(10.0, -o.onset_threshold_db / 10.0);
  m.onset_sample = 0;
  while (m.onset_sample < n && (double)h[m.onset_sample] * h[m.onset_sample] < onset_level) ++m.onset_sample;
  const size_t onset = m.onset_sample;
  const size_t te = (size_t)std::lround(o.clarity_time_ms * 1e-3 * fs);
  if (onset + te >= n) {
    throw Error(rir_name(rir) + ": too short: " + format_double(1e3 * (n - onset) / fs, 4) +
                " ms after the onset, the clarity window needs more than " + format_double(o.clarity_time_ms) + " ms");
  }
  const size_t rem = n - onset;

  // Broadband decay, C50 and DRR.
  MetricsWorkspace& w = metrics_workspace();
  w.energy.resize(rem);
  for (size_t i = 0; i < rem; ++i) w.energy[i] = (double)h[onset + i] * h[onset + i];
  thread_local IsoDecay bb;
  backward_sums(w.energy.data(), rem, &w.tail);
  iso_decay(w.tail.data(), rem, fs, 0.0, o.lundeby, "broadband", &m.warnings, &bb);
  m.broadband = iso_band_metrics(bb, 0.0, fs, o.lundeby, "broadband", &m.warnings, &w.db);
  m.broadband.level_db = 0.0;

  const double early = energy_sum(h, onset, onset + te);
  const double late = iso_late_energy(bb, te, fs);
  m.c50_db = late > 0 ? 10.0 * std::log10(early / late) : kNaN;
  if (!(late > 0)) m.warnings.push_back("C50: no energy after " + format_double(o.clarity_time_ms) + " ms");
  iso_d50_c80(h, onset, fs, bb, &m);

  const long pre = std::lround(o.direct_pre_ms * 1e-3 * fs), post = std::lround(o.direct_post_ms * 1e-3 * fs);
  const size_t d_begin = (size_t)std::max<long>(0, (long)m.peak_sample - pre);
  const size_t d_end = std::min(n, m.peak_sample + (size_t)std::max<long>(0, post) + 1);
  const double direct = energy_sum(h, d_begin, d_end);
  // The reverberant part starts after the direct window; before the onset there is none.
  const double reverb = d_end >= onset ? iso_late_energy(bb, d_end - onset, fs) : iso_late_energy(bb, 0, fs);
  m.drr_db = reverb > 0 ? 10.0 * std::log10(direct / reverb) : kNaN;
  if (!(reverb > 0)) m.warnings.push_back("DRR: no energy after the direct window");

  // Octave bands, filtered time-reversed in one pass over the RIR.
  const std::vector<double> centers = metrics_band_centers_hz(fs, MetricsDefinition::kIso);
  std::vector<std::vector<double>>& y = w.bands;
  sos_filter_bank(band_filters(fs, centers), h.data(), n, /*time_reversed=*/true, &y);
  IsoDecay& d = bb;  // the broadband curve is no longer needed
  const double total = energy_sum(h, 0, n);
  std::vector<double> band_total, band_peak;
  square_bands(&y, n, &band_total, &band_peak);
  backward_sums_interleaved(y, n, &w.band_tails);
  for (size_t b = 0; b < centers.size(); ++b) {
    const std::string label = band_name(centers[b]);
    // Time-reversed filtering moves part of the band's direct sound ahead of the broadband onset;
    // the band EDC starts at the band's own onset when that is earlier, so all of it is counted
    // (otherwise E(0) is too small, the -5 dB point moves into the later, often slower decay and
    // T30 comes out long: +2 % on average over the R3VIVAL set, up to +5.5 %).
    const double band_onset_level = band_peak[b] * std::pow(10.0, -o.onset_threshold_db / 10.0);
    size_t start = 0;
    while (start < onset && y[b][start] < band_onset_level) ++start;
    iso_decay(w.band_tails[b].data() + start, n - start, fs, centers[b], o.lundeby, label, &m.warnings, &d);
    BandMetrics bm = iso_band_metrics(d, centers[b], fs, o.lundeby, label, &m.warnings, &w.db);
    bm.level_db = band_total[b] > 0 ? 10.0 * std::log10(band_total[b] / total) : -INFINITY;
    // ISO 3382-1: time-reversed filtering stays unbiased for bandwidth * T > 4.
    const BandEdgesHz edges = ansi_octave_edges_hz(centers[b], kOctaveOrder);
    if (std::isfinite(bm.rt_s) && (edges.high_hz - edges.low_hz) * bm.rt_s < 4.0) {
      m.warnings.push_back(label + ": bandwidth x T = " + format_double((edges.high_hz - edges.low_hz) * bm.rt_s, 3) +
                           " < 4, the band filter may lengthen this decay");
    }
    m.bands.push_back(bm);
  }
  set_mid_band_values(&m);
  return m;
}

}  // namespace tsrir::metrics_detail
