// ISO 3382-1 parameters (MetricsDefinition::kIso): onset 20 dB below the peak, Schroeder decay with
// noise subtraction, Lundeby truncation and compensation, octave bands filtered time-reversed.
#include "metrics/metrics_iso.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "dsp/bands.h"
#include "metrics/decay_fit.h"
#include "metrics/lundeby.h"
#include "metrics/metrics_common.h"
#include "util/cpu_clones.h"
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

typedef double Doubles4 __attribute__((vector_size(32)));
typedef long long Masks4 __attribute__((vector_size(32)));

// The first k in [0, end) with edc[k] <= 0 (or NaN), else `end`: blocks of 8 compared without an
// early exit (vector compares), the block holding the first such value scanned one by one.
TSRIR_AVX2_CLONES
size_t first_not_positive(const double* edc, size_t end) {
  const Doubles4 zero = {0, 0, 0, 0};
  size_t k = 0;
  for (; k + 8 <= end; k += 8) {
    Doubles4 a, b;
    std::memcpy(&a, edc + k, sizeof a);
    std::memcpy(&b, edc + k + 4, sizeof b);
    const Masks4 positive = (a > zero) & (b > zero);  // all ones where both are > 0
    if (!(positive[0] & positive[1] & positive[2] & positive[3])) break;
  }
  while (k < end && edc[k] > 0) ++k;
  return k;
}

// edc[k] = (tail[k] - cut) - noise (end - k) + tail_energy for k in [0, end); returns whether every
// value is > 0. Four at a time as vectors (four wide in the AVX2 clone, which has no FMA, so each
// value is rounded as the scalar formula rounds it); the counts end - k run as exact doubles.
TSRIR_AVX2_CLONES
bool compensated_edc(const double* tail, size_t end, double cut, double noise, double tail_energy, double* edc) {
  const Doubles4 zero = {0, 0, 0, 0};
  const Doubles4 cut4 = {cut, cut, cut, cut}, noise4 = {noise, noise, noise, noise};
  const Doubles4 tail4 = {tail_energy, tail_energy, tail_energy, tail_energy};
  const double count = (double)end;
  Doubles4 counts = {count, count - 1, count - 2, count - 3};
  Masks4 positive = {-1, -1, -1, -1};
  size_t k = 0;
  for (; k + 4 <= end; k += 4) {
    Doubles4 t;
    std::memcpy(&t, tail + k, sizeof t);
    const Doubles4 v = (t - cut4) - noise4 * counts + tail4;
    std::memcpy(edc + k, &v, sizeof v);
    positive &= v > zero;
    counts -= 4.0;
  }
  bool all = positive[0] && positive[1] && positive[2] && positive[3];
  for (; k < end; ++k) {
    edc[k] = (tail[k] - cut) - noise * (double)(end - k) + tail_energy;
    all = all && edc[k] > 0;
  }
  return all;
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
    const bool positive = compensated_edc(tail, end, cut, noise, tail_energy, edc);
    // Noise fluctuations can drive the last values to zero or below: those are not measured.
    if (!positive) end = first_not_positive(edc, end);
  } else {
    std::copy(tail, tail + end, edc);
  }
  d->usable_end = end;
}

// Each band's energy summed from the first sample on (as the level has always been): the bands of
// a row side by side, so each band's sum runs in its own order and the rows' adds vectorise. The
// broadband energy (energy_sum(h, 0, n), same order) is added alongside, its chain overlapping.
TSRIR_AVX2_CLONES
std::vector<double> band_totals(const BankEnergies& y, const float* h, size_t n, double* broadband) {
  std::vector<double> total(y.stride, 0.0);
  *broadband = 0.0;
  for (size_t c = 0; c + 8 <= y.stride; c += 8) {
    Doubles4 low = {0, 0, 0, 0}, high = {0, 0, 0, 0};  // bands c .. c + 7, kept in registers
    double all = 0.0;
    const double* e = y.energy.data() + c;
    for (size_t i = 0; i < n; ++i, e += y.stride) {
      Doubles4 a, b;
      std::memcpy(&a, e, sizeof a);
      std::memcpy(&b, e + 4, sizeof b);
      low += a;
      high += b;
      all += (double)h[i] * h[i];
    }
    std::memcpy(&total[c], &low, sizeof low);
    std::memcpy(&total[c + 4], &high, sizeof high);
    *broadband = all;
  }
  total.resize(y.tail.size());
  return total;
}

// max_i h[i]^2 (exact: a maximum does not depend on the order), four at a time as vectors.
TSRIR_AVX2_CLONES
double peak_energy(const float* h, size_t n) {
  typedef float Floats4 __attribute__((vector_size(16)));
  Doubles4 top = {0, 0, 0, 0};
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    Floats4 x;
    std::memcpy(&x, h + i, sizeof x);
    const Doubles4 d = __builtin_convertvector(x, Doubles4);
    const Doubles4 e = d * d;
    top = top < e ? e : top;
  }
  double peak = std::max(std::max(top[0], top[1]), std::max(top[2], top[3]));
  for (; i < n; ++i) peak = std::max(peak, (double)h[i] * h[i]);
  return peak;
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
  // EDT, T20, T30, the measurable ones fitted together (fit_decay_ranges).
  const DecayRangeDb ranges[3] = {{0.0, -10.0}, {-5.0, -25.0}, {-5.0, -35.0}};
  double* decay_s[3] = {&b.edt_s, &b.t20_s, &b.t30_s};
  std::vector<DecayRangeDb> measurable;
  std::vector<double*> results;
  for (int r = 0; r < 3; ++r) {
    *decay_s[r] = kNaN;
    if (std::isfinite(psnr) && psnr < -ranges[r].lower_db + 10.0) continue;
    measurable.push_back(ranges[r]);
    results.push_back(decay_s[r]);
  }
  std::vector<DecayFit> fits;
  fit_decay_ranges(d.edc.data(), db->data(), d.usable_end, d.edc[0], fs, measurable, &fits);
  for (size_t k = 0; k < fits.size(); ++k) *results[k] = fits[k].decay_time_s();
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

  const double peak_e = peak_energy(h.data(), n);
  // The first sample at the peak (as a strict > search keeps it).
  m.peak_sample = 0;
  while ((double)h[m.peak_sample] * h[m.peak_sample] != peak_e) ++m.peak_sample;
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
  // Squared and integrated backwards in the same pass (the Schroeder sums run the same way).
  BankEnergies& y = w.band_energies;
  sos_filter_bank_energies(band_filters(fs, centers), h.data(), n, &y);
  IsoDecay& d = bb;  // the broadband curve is no longer needed
  double total = 0.0;
  const std::vector<double> band_total = band_totals(y, h.data(), n, &total);
  for (size_t b = 0; b < centers.size(); ++b) {
    const std::string label = band_name(centers[b]);
    // Time-reversed filtering moves part of the band's direct sound ahead of the broadband onset;
    // the band EDC starts at the band's own onset when that is earlier, so all of it is counted
    // (otherwise E(0) is too small, the -5 dB point moves into the later, often slower decay and
    // T30 comes out long: +2 % on average over the R3VIVAL set, up to +5.5 %).
    const double band_onset_level = y.peak[b] * std::pow(10.0, -o.onset_threshold_db / 10.0);
    size_t start = 0;
    while (start < onset && y.at(b, start) < band_onset_level) ++start;
    iso_decay(y.tail[b].data() + start, n - start, fs, centers[b], o.lundeby, label, &m.warnings, &d);
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
