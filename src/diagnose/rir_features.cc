#include "diagnose/rir_features.h"

#include <algorithm>
#include <cmath>

#include "diagnose/set_statistics.h"
#include "dsp/convolve.h"
#include "dsp/fft.h"
#include "dsp/octave_filter.h"

namespace tsrir::diagnose {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLn60dB = 13.815510557964274;

double db(double power) { return power > 0.0 ? 10.0 * std::log10(power) : -300.0; }

bool band_below_nyquist(int band, double fs) { return octave_upper_edge_hz(kOctaveCentersHz[band]) < 0.5 * fs; }

double onset_position(const std::vector<float>& h) {
  float peak = 0.0f;
  for (float x : h) peak = std::max(peak, std::abs(x));
  size_t first = 0;
  while (first < h.size() && std::abs(h[first]) < 0.25f * peak) ++first;
  // The local maximum of |h| right after the first strong sample (within 16 samples).
  size_t best = first;
  for (size_t i = first; i < std::min(h.size(), first + 16); ++i) {
    if (std::abs(h[i]) > std::abs(h[best])) best = i;
  }
  if (best == 0 || best + 1 >= h.size()) return static_cast<double>(best);
  const double a = std::abs(h[best - 1]), b = std::abs(h[best]), c = std::abs(h[best + 1]);
  const double denom = a - 2.0 * b + c;
  return best + (denom < 0.0 ? 0.5 * (a - c) / denom : 0.0);
}

// Energy per octave band of h[begin, end) (raised-cosine edges of `taper` samples), by FFT.
BandValues window_band_energy(const std::vector<float>& h, long begin, long end, size_t taper, double fs) {
  BandValues out;
  out.fill(NAN);
  begin = std::max(0L, begin);
  end = std::min<long>(static_cast<long>(h.size()), end);
  if (end - begin < 8) return out;
  const size_t len = static_cast<size_t>(end - begin);
  std::vector<float> w(h.begin() + begin, h.begin() + end);
  for (size_t i = 0; i < taper && i < len / 2; ++i) {
    const float g = static_cast<float>(0.5 * (1.0 - std::cos(kPi * (i + 0.5) / taper)));
    w[i] *= g;
    w[len - 1 - i] *= g;
  }
  size_t n = 1;
  while (n < std::max<size_t>(len, static_cast<size_t>(fs / 16.0))) n *= 2;
  const std::vector<double> p = power_spectrum(w, n);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const double lo = octave_lower_edge_hz(kOctaveCentersHz[b]), hi = octave_upper_edge_hz(kOctaveCentersHz[b]);
    if (lo >= 0.5 * fs) continue;
    double e = 0.0;
    for (size_t k = 0; k < p.size(); ++k) {
      const double f = k * fs / n;
      if (f >= lo && f < hi) e += p[k];
    }
    out[b] = e;
  }
  return out;
}

// How much a band still decays near the end of the file: level of [70 %, 80 %) of the length
// minus level of [90 %, 100 %). An exponential decay of any rate gives 60 dB * 0.2 length / T60
// (> 5 dB for every plausible room and 1 s files); stationary noise gives ~0.
double band_late_decay_db(const std::vector<double>& y) {
  const size_t n = y.size();
  auto level = [&](size_t a, size_t b) {
    double e = 0.0;
    for (size_t k = a; k < b; ++k) e += y[k] * y[k];
    return db(e / std::max<size_t>(1, b - a));
  };
  return level(7 * n / 10, 8 * n / 10) - level(9 * n / 10, n);
}

// The band the echo-density statistic reads (FeatureOptions::echo_density_low_hz..high_hz, the
// top capped at 0.45 fs), as float samples for mean_echo_density.
std::vector<float> echo_density_band(const std::vector<float>& h, double fs, const FeatureOptions& options) {
  const double high_hz = std::min(options.echo_density_high_hz, 0.45 * fs);
  const std::vector<double> band = sos_filter(butterworth_bandpass(2, options.echo_density_low_hz, high_hz, fs), h);
  return std::vector<float>(band.begin(), band.end());
}

}  // namespace

bool direct_band_reliable(int band, double fs) {
  return kOctaveCentersHz[band] >= 500.0 && octave_lower_edge_hz(kOctaveCentersHz[band]) < 0.45 * fs;
}

double mean_echo_density(const std::vector<float>& x, double fs, size_t begin, size_t end) {
  const size_t half = static_cast<size_t>(0.005 * fs);
  const size_t step = std::max<size_t>(1, static_cast<size_t>(0.001 * fs));
  const double erfc_norm = std::erfc(1.0 / std::sqrt(2.0));
  double sum = 0.0;
  int count = 0;
  for (size_t c = begin; c < end && c + half < x.size(); c += step) {
    if (c < half) continue;
    double e = 0.0;
    for (size_t i = c - half; i < c + half; ++i) e += double(x[i]) * x[i];
    const double sd = std::sqrt(e / (2 * half));
    if (sd <= 0.0) continue;
    size_t beyond = 0;
    for (size_t i = c - half; i < c + half; ++i) beyond += std::abs(x[i]) > sd;
    sum += static_cast<double>(beyond) / (2 * half) / erfc_norm;
    ++count;
  }
  return count ? sum / count : NAN;
}

double lf_spectral_distance_db(const std::vector<double>& a, const std::vector<double>& b, double lf_min_hz) {
  const size_t begin = static_cast<size_t>(std::ceil(lf_min_hz));
  const size_t end = std::min(a.size(), b.size());
  if (end <= begin + 2) return NAN;
  std::vector<double> d;
  for (size_t k = begin; k < end; ++k) d.push_back(a[k] - b[k]);
  const double m = mean_of(d);
  double s = 0.0;
  for (double v : d) s += (v - m) * (v - m);
  return std::sqrt(s / d.size());
}

std::vector<double> edc_db_curve(const Signal& rir, double onset_s, double step_s, double length_s) {
  const size_t onset = std::min(rir.size(), static_cast<size_t>(std::max(0.0, onset_s) * rir.sample_rate_hz));
  const std::vector<double> edc = schroeder_decay_db(rir.samples, onset);
  std::vector<double> out;
  for (double t = 0.0; t <= length_s; t += step_s) {
    const size_t i = static_cast<size_t>(t * rir.sample_rate_hz);
    out.push_back(i < edc.size() ? std::max(edc[i], -120.0) : NAN);
  }
  return out;
}

double onset_time_s(const Signal& rir) { return onset_position(rir.samples) / rir.sample_rate_hz; }

RirFeatures compute_features(const Signal& rir, const std::vector<double>& mode_freqs_hz, double schroeder_hz,
                             double t60_low_s, const FeatureOptions& options) {
  const double fs = rir.sample_rate_hz;
  const std::vector<float>& h = rir.samples;
  RirFeatures f;
  const double onset = onset_position(h);
  f.onset_s = onset / fs;
  for (float x : h) f.energy += double(x) * x;

  MetricsOptions mo;
  mo.definition = MetricsDefinition::kIso;
  mo.lundeby = true;
  f.metrics = measure_rir(rir, mo);
  f.decay_rate_per_s.fill(NAN);
  f.t30_s.fill(NAN);
  f.early_decay_rate_per_s.fill(NAN);
  f.level_db.fill(NAN);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const BandMetrics* m = f.metrics.band(kOctaveCentersHz[b]);
    if (!m) continue;
    f.t30_s[b] = m->t30_s;
    // T30 where the dynamic range allows it, else T20 (long low-band decays in 1 s files).
    const double t = std::isfinite(m->t30_s) && m->t30_s > 0 ? m->t30_s : m->t20_s;
    f.decay_rate_per_s[b] = std::isfinite(t) && t > 0 ? kLn60dB / t : NAN;
    f.early_decay_rate_per_s[b] = std::isfinite(m->edt_s) && m->edt_s > 0 ? kLn60dB / m->edt_s : NAN;
    f.level_db[b] = m->level_db;
  }

  const long on = static_cast<long>(std::floor(onset));
  const size_t taper = std::max<size_t>(2, static_cast<size_t>(0.00025 * fs));
  const BandValues direct = window_band_energy(h, on - static_cast<long>(options.direct_pre_ms * 1e-3 * fs),
                                               on + static_cast<long>(options.direct_post_ms * 1e-3 * fs), taper, fs);
  const BandValues tail = window_band_energy(h, on + static_cast<long>(options.tail_begin_ms * 1e-3 * fs),
                                             on + static_cast<long>(options.tail_end_ms * 1e-3 * fs), 4 * taper, fs);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    f.direct_band_db[b] = direct_band_reliable(b, fs) && std::isfinite(direct[b]) ? db(direct[b]) : NAN;
    f.tail_band_db[b] = std::isfinite(tail[b]) ? db(tail[b]) : NAN;
  }

  // Late power and tail excess per octave band (causal ANSI filters; the filters' ringing is far
  // below the levels compared here).
  const size_t n = h.size();
  const size_t late_begin = n - std::max<size_t>(1, n / 10);
  std::vector<double> late_decay;
  f.late_power.fill(NAN);
  f.late_decay_band_db.fill(NAN);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (!band_below_nyquist(b, fs)) continue;
    const std::vector<double> y = sos_filter(ansi_octave_filter(kOctaveCentersHz[b], fs, 3), h);
    double p = 0.0;
    for (size_t i = late_begin; i < n; ++i) p += y[i] * y[i];
    f.late_power[b] = p / (n - late_begin);
    f.late_decay_band_db[b] = band_late_decay_db(y);
    if (kOctaveCentersHz[b] >= 500.0 && kOctaveCentersHz[b] <= 4000.0) {
      late_decay.push_back(band_late_decay_db(y));
    }
  }
  f.late_decay_db = median_of(late_decay);
  double late_e = 0.0;
  for (size_t i = late_begin; i < n; ++i) late_e += double(h[i]) * h[i];
  f.tail_level_db = db(late_e / std::max(f.energy, 1e-300));

  // Echo density of the mid/high band (low frequencies would measure the room's modes, not its
  // reflections).
  const std::vector<float> bandf = echo_density_band(h, fs, options);
  const size_t ed_begin = static_cast<size_t>(std::max(0.0, onset + options.echo_density_begin_ms * 1e-3 * fs));
  const size_t ed_end = static_cast<size_t>(std::max(0.0, onset + options.echo_density_end_ms * 1e-3 * fs));
  f.echo_density = mean_echo_density(bandf, fs, ed_begin, ed_end);

  // Low-frequency spectrum of the response from the onset on, 0.25 Hz resolution or finer.
  const std::vector<float> from_onset(h.begin() + std::min<size_t>(n, std::max(0L, on)), h.end());
  const size_t nfft = next_fast_fft_size(std::max<size_t>(from_onset.size(), static_cast<size_t>(4.0 * fs)));
  const std::vector<double> p = power_spectrum(from_onset, nfft);
  const double df = fs / nfft;
  double total = 0.0, low = 0.0;
  for (size_t k = 0; k < p.size(); ++k) {
    total += p[k];
    if (k * df < schroeder_hz) low += p[k];
  }
  f.lf_energy_ratio = total > 0 ? low / total : NAN;
  const size_t lf_bins = static_cast<size_t>(options.lf_max_hz) + 1;
  f.lf_spectrum_db.assign(lf_bins, NAN);
  for (size_t k = 0; k < lf_bins; ++k) {
    double s = 0.0;
    int c = 0;
    for (size_t j = static_cast<size_t>(std::max(0.0, (k - 1.5) / df)); j * df <= k + 1.5 && j < p.size(); ++j) {
      s += p[j];
      ++c;
    }
    f.lf_spectrum_db[k] = db(c ? s / c : 0.0);
  }
  // Mode prominence: the late spectrum's maximum within the modal half-bandwidth of each predicted
  // mode, minus the mean of the same window maximum taken on a grid (one half-bandwidth apart)
  // over the whole range of predicted modes, each taken relative to the local spectral level
  // (mean dB over +-kTrendHz around it). Both are window maxima of the same spectrum, so for a
  // response whose peaks do not sit at the predicted modes the difference is zero; the local
  // reference removes any smooth trend (a loudspeaker's low-frequency roll-off would otherwise
  // read as modes). The grid reference replaced maxima at the midpoints of wide gaps between
  // modes: a handful of midpoints per RIR made the reference, and so the statistic, about three
  // times noisier (per-RIR s.d. 1.1 dB against 0.4 dB; docs/results/diagnose_power.md).
  constexpr double kTrendHz = 10.0;
  const double tol_hz = std::max(0.75, 1.1 / std::max(t60_low_s, 0.1));
  const size_t late_begin_mode =
      std::min(n, static_cast<size_t>(std::max(0L, on)) + static_cast<size_t>(options.mode_spectrum_begin_ms * 1e-3 * fs));
  const std::vector<float> late_part(h.begin() + late_begin_mode, h.end());
  const std::vector<double> pl = late_part.size() >= 16 ? power_spectrum(late_part, nfft) : std::vector<double>();
  auto window_max = [&](double centre) {
    double best = -300.0;
    for (size_t k = static_cast<size_t>(std::max(0.0, (centre - tol_hz) / df)); k * df <= centre + tol_hz && k < pl.size(); ++k) {
      best = std::max(best, db(pl[k]));
    }
    return best;
  };
  auto local_level = [&](double centre) {
    double sum = 0.0;
    int count = 0;
    for (size_t k = static_cast<size_t>(std::max(0.0, (centre - kTrendHz) / df)); k * df <= centre + kTrendHz && k < pl.size(); ++k) {
      sum += db(pl[k]);
      ++count;
    }
    return count ? sum / count : 0.0;
  };
  std::vector<double> in_range;
  for (double fm : mode_freqs_hz) {
    if (fm >= options.lf_min_hz && fm <= schroeder_hz) in_range.push_back(fm);
  }
  std::sort(in_range.begin(), in_range.end());
  double peak_sum = 0.0, grid_sum = 0.0;
  int peak_n = 0, grid_n = 0;
  if (!pl.empty()) {
    for (double fm : in_range) {
      peak_sum += window_max(fm) - local_level(fm);
      ++peak_n;
    }
    if (!in_range.empty()) {
      for (double c = in_range.front(); c <= in_range.back(); c += tol_hz) {
        grid_sum += window_max(c) - local_level(c);
        ++grid_n;
      }
    }
  }
  f.mode_prominence_db = (peak_n >= 3 && grid_n >= 3) ? peak_sum / peak_n - grid_sum / grid_n : NAN;
  return f;
}

std::pair<double, double> cross_equalised_echo_density(const Signal& x, double onset_x_s, const Signal& y,
                                                       double onset_y_s, const FeatureOptions& options) {
  const double fs = x.sample_rate_hz;
  auto direct = [&](const Signal& s, double onset_s) {
    const long a = std::max(0L, static_cast<long>(std::lround((onset_s - 0.0005) * fs)));
    const long b = std::min<long>(static_cast<long>(s.size()), static_cast<long>(std::lround((onset_s + 0.0015) * fs)));
    std::vector<float> d(s.samples.begin() + std::min<long>(a, s.size()), s.samples.begin() + std::max(a, b));
    double e = 0.0;
    for (float v : d) e += double(v) * v;
    for (float& v : d) v = static_cast<float>(v / std::sqrt(std::max(e, 1e-300)));
    return d;
  };
  auto density = [&](const Signal& s, double onset_s, const std::vector<float>& eq) {
    std::vector<float> z = fft_convolve(s.samples, eq);
    z.resize(s.size());
    const std::vector<float> bandf = echo_density_band(z, fs, options);
    const double start = onset_s + 0.0005;
    return mean_echo_density(bandf, fs, static_cast<size_t>(std::max(0.0, (start + options.echo_density_begin_ms * 1e-3) * fs)),
                             static_cast<size_t>(std::max(0.0, (start + options.echo_density_end_ms * 1e-3) * fs)));
  };
  return {density(x, onset_x_s, direct(y, onset_y_s)), density(y, onset_y_s, direct(x, onset_x_s))};
}
}  // namespace tsrir::diagnose
