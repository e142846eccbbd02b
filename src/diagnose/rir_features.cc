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

namespace {

// ISO decay parameters (Lundeby noise handling) and the per-band decay rates and levels from them.
void decay_features(const Signal& rir, RirFeatures* f) {
  MetricsOptions mo;
  mo.definition = MetricsDefinition::kIso;
  mo.lundeby = true;
  f->metrics = measure_rir(rir, mo);
  f->decay_rate_per_s.fill(NAN);
  f->t30_s.fill(NAN);
  f->early_decay_rate_per_s.fill(NAN);
  f->level_db.fill(NAN);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const BandMetrics* m = f->metrics.band(kOctaveCentersHz[b]);
    if (!m) continue;
    f->t30_s[b] = m->t30_s;
    // T30 where the dynamic range allows it, else T20 (long low-band decays in 1 s files).
    const double t = std::isfinite(m->t30_s) && m->t30_s > 0 ? m->t30_s : m->t20_s;
    f->decay_rate_per_s[b] = std::isfinite(t) && t > 0 ? kLn60dB / t : NAN;
    f->early_decay_rate_per_s[b] = std::isfinite(m->edt_s) && m->edt_s > 0 ? kLn60dB / m->edt_s : NAN;
    f->level_db[b] = m->level_db;
  }
}

// Band levels of the direct-sound window and of the reverberant window after the onset.
void window_features(const std::vector<float>& h, long on, double fs, const FeatureOptions& options, RirFeatures* f) {
  const size_t taper = std::max<size_t>(2, static_cast<size_t>(0.00025 * fs));
  const BandValues direct = window_band_energy(h, on - static_cast<long>(options.direct_pre_ms * 1e-3 * fs),
                                               on + static_cast<long>(options.direct_post_ms * 1e-3 * fs), taper, fs);
  const BandValues tail = window_band_energy(h, on + static_cast<long>(options.tail_begin_ms * 1e-3 * fs),
                                             on + static_cast<long>(options.tail_end_ms * 1e-3 * fs), 4 * taper, fs);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    f->direct_band_db[b] = direct_band_reliable(b, fs) && std::isfinite(direct[b]) ? db(direct[b]) : NAN;
    f->tail_band_db[b] = std::isfinite(tail[b]) ? db(tail[b]) : NAN;
  }
}

// Where the response is above digital silence (RirFeatures::active_end_s), and its energy per 10 ms
// block.
void span_features(const std::vector<float>& h, double fs, RirFeatures* f) {
  const size_t block = std::max<size_t>(1, static_cast<size_t>(0.01 * fs));
  double peak_block = 0.0;
  for (size_t a = 0; a < h.size(); a += block) {
    double e = 0.0;
    for (size_t i = a; i < std::min(h.size(), a + block); ++i) e += double(h[i]) * h[i];
    f->block_energy.push_back(e / std::max(f->energy, 1e-300));
    peak_block = std::max(peak_block, f->block_energy.back());
  }
  size_t active = f->block_energy.size();
  while (active > 0 && !(f->block_energy[active - 1] > peak_block * std::pow(10.0, -kSilenceDb / 10.0))) --active;
  f->active_end_s = std::min(h.size(), active * block) / fs;
}

// Late power and decay per octave band (causal ANSI filters; the filters' ringing is far below the
// levels compared here) and the tail level, over the active part's last 10 % and 30 %.
void late_features(const std::vector<float>& h, double fs, RirFeatures* f) {
  const size_t n = std::max<size_t>(1, std::min(h.size(), static_cast<size_t>(std::lround(f->active_end_s * fs))));
  const std::vector<float> active(h.begin(), h.begin() + n);
  const size_t late_begin = n - std::max<size_t>(1, n / 10);
  std::vector<double> late_decay;
  f->late_power.fill(NAN);
  f->late_decay_band_db.fill(NAN);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (!band_below_nyquist(b, fs)) continue;
    const std::vector<double> y = sos_filter(ansi_octave_filter(kOctaveCentersHz[b], fs, 3), active);
    double p = 0.0;
    for (size_t i = late_begin; i < n; ++i) p += y[i] * y[i];
    f->late_power[b] = p / (n - late_begin);
    f->late_decay_band_db[b] = band_late_decay_db(y);
    if (kOctaveCentersHz[b] >= 500.0 && kOctaveCentersHz[b] <= 4000.0) late_decay.push_back(f->late_decay_band_db[b]);
  }
  f->late_decay_db = median_of(late_decay);
  double late_e = 0.0;
  for (size_t i = late_begin; i < n; ++i) late_e += double(active[i]) * active[i];
  f->tail_level_db = db(late_e / std::max(f->energy, 1e-300));
}

// Low-frequency spectrum of the response from the onset on (0.25 Hz resolution or finer, 3 Hz
// power smoothing on a 1 Hz grid) and the energy share below the Schroeder frequency.
void low_frequency_features(const std::vector<float>& h, size_t onset, double fs, double schroeder_hz,
                            const FeatureOptions& options, RirFeatures* f) {
  const std::vector<float> from_onset(h.begin() + std::min(h.size(), onset), h.end());
  const size_t nfft = next_fast_fft_size(std::max<size_t>(from_onset.size(), static_cast<size_t>(4.0 * fs)));
  const std::vector<double> p = power_spectrum(from_onset, nfft);
  const double df = fs / nfft;
  double total = 0.0, low = 0.0;
  for (size_t k = 0; k < p.size(); ++k) {
    total += p[k];
    if (k * df < schroeder_hz) low += p[k];
  }
  f->lf_energy_ratio = total > 0 ? low / total : NAN;
  const size_t lf_bins = static_cast<size_t>(options.lf_max_hz) + 1;
  f->lf_spectrum_db.assign(lf_bins, NAN);
  for (size_t k = 0; k < lf_bins; ++k) {
    double s = 0.0;
    int c = 0;
    for (size_t j = static_cast<size_t>(std::max(0.0, (k - 1.5) / df)); j * df <= k + 1.5 && j < p.size(); ++j) {
      s += p[j];
      ++c;
    }
    f->lf_spectrum_db[k] = db(c ? s / c : 0.0);
  }
}

// The fine structure of the power spectrum of h[begin, end) (10 % Tukey window) from lo_hz to
// hi_hz: each bin's power over the mean power within +-trend_hz (a smooth trend, such as a
// loudspeaker's roll-off or the room's decay per band, divides out).
std::vector<double> fine_structure(const std::vector<float>& h, size_t begin, size_t end, double fs, double lo_hz,
                                   double hi_hz, double trend_hz) {
  std::vector<float> w(h.begin() + begin, h.begin() + end);
  const size_t taper = w.size() / 10;
  for (size_t i = 0; i < taper; ++i) {
    const float g = static_cast<float>(0.5 - 0.5 * std::cos(kPi * (i + 0.5) / taper));
    w[i] *= g;
    w[w.size() - 1 - i] *= g;
  }
  const size_t nfft = next_fast_fft_size(static_cast<size_t>(2.0 * fs));  // a 0.5 Hz grid
  const std::vector<double> p = power_spectrum(w, nfft);
  const double df = fs / nfft;
  std::vector<double> prefix(p.size() + 1, 0.0);
  for (size_t k = 0; k < p.size(); ++k) prefix[k + 1] = prefix[k] + p[k];
  const long half = static_cast<long>(std::lround(trend_hz / df));
  std::vector<double> out;
  for (long k = static_cast<long>(std::ceil(lo_hz / df)); k * df <= hi_hz && k < static_cast<long>(p.size()); ++k) {
    const long a = std::max(0L, k - half), b = std::min<long>(static_cast<long>(p.size()), k + half + 1);
    const double local = (prefix[b] - prefix[a]) / (b - a);
    out.push_back(local > 0.0 ? p[k] / local : 0.0);
  }
  return out;
}

// Late-field spectral persistence per pair of consecutive windows (FeatureOptions::persistence_*).
void persistence_features(const std::vector<float>& h, size_t onset, double fs, double schroeder_hz,
                          const FeatureOptions& options, RirFeatures* f) {
  const size_t begin = onset + static_cast<size_t>(options.persistence_begin_ms * 1e-3 * fs);
  const size_t len = static_cast<size_t>(options.persistence_window_ms * 1e-3 * fs);
  const size_t active = static_cast<size_t>(std::lround(f->active_end_s * fs));
  const double hi_hz = options.persistence_schroeder_factor * schroeder_hz;
  std::vector<std::vector<double>> windows;
  for (int w = 0; w < options.persistence_windows; ++w) {
    const size_t a = begin + w * len;
    windows.push_back(a + len <= std::min(active, h.size()) && hi_hz > options.lf_min_hz + 2.0 * options.persistence_trend_hz
                          ? fine_structure(h, a, a + len, fs, options.lf_min_hz, hi_hz, options.persistence_trend_hz)
                          : std::vector<double>());
  }
  for (size_t w = 0; w + 1 < windows.size(); ++w) {
    const bool ok = windows[w].size() >= 8 && windows[w].size() == windows[w + 1].size();
    f->persistence_pairs.push_back(ok ? correlation(windows[w], windows[w + 1]) : NAN);
  }
}

}  // namespace

double tail_level_in_window_db(const RirFeatures& f, const RirFeatures& reference) {
  const size_t end = std::min(f.block_energy.size(), static_cast<size_t>(std::lround(reference.active_end_s / 0.01)));
  const size_t begin = end - std::min(end, std::max<size_t>(1, end / 10));
  double e = 0.0;
  for (size_t k = begin; k < end; ++k) e += f.block_energy[k];
  return end > begin ? db(e) : NAN;
}

size_t persistence_pairs_in_span(const RirFeatures& reference, const FeatureOptions& options) {
  size_t pairs = 0;
  for (size_t p = 0; p < reference.persistence_pairs.size(); ++p) {
    const double end_s = reference.onset_s + 1e-3 * (options.persistence_begin_ms + (p + 2) * options.persistence_window_ms);
    if (end_s > reference.active_end_s || !std::isfinite(reference.persistence_pairs[p])) break;
    ++pairs;
  }
  return pairs;
}

double mean_persistence(const RirFeatures& f, size_t pairs) {
  double s = 0.0;
  size_t c = 0;
  for (size_t p = 0; p < pairs && p < f.persistence_pairs.size(); ++p) {
    if (std::isfinite(f.persistence_pairs[p])) { s += f.persistence_pairs[p]; ++c; }
  }
  return c == pairs && c > 0 ? s / c : NAN;
}

RirFeatures compute_features(const Signal& rir, double schroeder_hz, const FeatureOptions& options) {
  const double fs = rir.sample_rate_hz;
  const std::vector<float>& h = rir.samples;
  RirFeatures f;
  const double onset = onset_position(h);
  f.onset_s = onset / fs;
  for (float x : h) f.energy += double(x) * x;
  const size_t on = static_cast<size_t>(std::max(0.0, std::floor(onset)));
  decay_features(rir, &f);
  window_features(h, static_cast<long>(on), fs, options, &f);
  span_features(h, fs, &f);
  late_features(h, fs, &f);
  // Echo density of the mid/high band (low frequencies would measure the room's modes, not its
  // reflections).
  const std::vector<float> bandf = echo_density_band(h, fs, options);
  const size_t ed_begin = static_cast<size_t>(std::max(0.0, onset + options.echo_density_begin_ms * 1e-3 * fs));
  const size_t ed_end = static_cast<size_t>(std::max(0.0, onset + options.echo_density_end_ms * 1e-3 * fs));
  f.echo_density = mean_echo_density(bandf, fs, ed_begin, ed_end);
  low_frequency_features(h, on, fs, schroeder_hz, options, &f);
  persistence_features(h, on, fs, schroeder_hz, options, &f);
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
