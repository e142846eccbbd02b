#include "perturb/rir_perturb.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dsp/fft.h"
#include "metrics/lundeby.h"
#include "metrics/rir_metrics.h"
#include "util/error.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNoiseFadeS = 0.020;   // fade before the noise floor when a decay is stretched
constexpr double kDirectRampS = 0.0005; // raised-cosine ramps inside the direct window
constexpr double kRingingRiseS = 0.002;

size_t samples_of(double seconds, double rate_hz) { return size_t(std::lround(seconds * rate_hz)); }

// 0 -> 1 over [0, 1] as a raised cosine.
double raised_cosine(double x) { return x <= 0 ? 0.0 : x >= 1 ? 1.0 : 0.5 - 0.5 * std::cos(kPi * x); }

// The first sample after which only measurement noise is left: Lundeby's intersection of the
// broadband decay from the onset (n when the noise cannot be told from the decay).
size_t noise_floor_start(const Signal& rir, size_t onset) {
  const size_t n = rir.size() - onset;
  std::vector<double> energy(n);
  for (size_t i = 0; i < n; ++i) energy[i] = double(rir.samples[onset + i]) * rir.samples[onset + i];
  const LundebyResult lundeby = lundeby_intersection(energy.data(), n, rir.sample_rate_hz, 0.0);
  return lundeby.ok ? onset + std::min(n, lundeby.intersection) : rir.size();
}

void fade_out_before(std::vector<float>& x, size_t end, size_t fade) {
  const size_t begin = end > fade ? end - fade : 0;
  for (size_t i = begin; i < x.size(); ++i) {
    x[i] *= i >= end ? 0.0f : float(1.0 - raised_cosine(double(i - begin) / double(end - begin)));
  }
}

void scale_decay(Signal& rir, const RirPerturbation& p, const RirMetrics& m, PerturbationRecord* record) {
  const double t60 = m.t60_s;
  if (!std::isfinite(t60) || t60 <= 0) {
    std::string why = m.warnings.empty() ? "" : " (" + m.warnings.front() + ")";
    throw Error("RIR '" + rir.id + "': its T60 cannot be measured, so its decay cannot be scaled" + why);
  }
  const double fs = rir.sample_rate_hz;
  const double k = 3.0 * std::log(10.0) * (1.0 / (p.t60_scale * t60) - 1.0 / t60);
  if (p.t60_scale > 1.0) {
    const size_t cut = noise_floor_start(rir, m.onset_sample);
    if (cut < rir.size()) {
      fade_out_before(rir.samples, cut, samples_of(kNoiseFadeS, fs));
      record->noise_cut_sample = cut;
    }
  }
  const size_t direct_end = m.peak_sample + samples_of(p.direct_post_ms / 1000.0, fs);
  for (size_t i = direct_end; i < rir.size(); ++i) {
    rir.samples[i] = float(rir.samples[i] * std::exp(-k * double(i - direct_end) / fs));
  }
  record->t60_in_s = t60;
  record->decay_rate_change_per_s = k;
}

void offset_direct(Signal& rir, const RirPerturbation& p, size_t peak) {
  const double fs = rir.sample_rate_hz;
  const double gain = std::pow(10.0, p.drr_offset_db / 20.0);
  const size_t pre = samples_of(p.direct_pre_ms / 1000.0, fs), post = samples_of(p.direct_post_ms / 1000.0, fs);
  const size_t begin = peak > pre ? peak - pre : 0;
  const size_t end = std::min(rir.size(), peak + post + 1);
  const double ramp = std::max(1.0, double(samples_of(kDirectRampS, fs)));
  for (size_t i = begin; i < end; ++i) {
    const double inside = std::min(double(i - begin + 1), double(end - i)) / ramp;
    rir.samples[i] = float(rir.samples[i] * (1.0 + (gain - 1.0) * raised_cosine(inside)));
  }
}

// Energy (sum of squares) of x below max_hz, from its spectrum (Parseval).
double energy_below(const std::vector<float>& x, double rate_hz, double max_hz) {
  const size_t n = next_fast_fft_size(x.size());
  const std::vector<double> power = power_spectrum(x, n);
  double sum = 0.0;
  for (size_t k = 0; k < power.size() && k * rate_hz / double(n) < max_hz; ++k) {
    const bool edge = k == 0 || (n % 2 == 0 && k == n / 2);
    sum += (edge ? 1.0 : 2.0) * power[k];
  }
  return sum / double(n);
}

void add_lf_ringing(Signal& rir, const RirPerturbation& p, size_t peak, std::uint64_t seed,
                    PerturbationRecord* record) {
  const double fs = rir.sample_rate_hz;
  const double own = energy_below(rir.samples, fs, p.lf_max_hz);
  if (!(own > 0)) throw Error("RIR '" + rir.id + "': no energy below " + format_double(p.lf_max_hz) + " Hz to scale ringing against");
  Rng rng = Rng::for_item(seed, "lf_ringing/" + rir.id);
  std::vector<double> ringing(rir.size() - peak, 0.0);
  const double rate = 3.0 * std::log(10.0) / p.lf_t60_s;   // amplitude decay per second
  for (int mode = 0; mode < kLfModes; ++mode) {
    const double f = p.lf_min_hz * std::pow(p.lf_max_hz / p.lf_min_hz, rng.uniform());
    const double phase = 2.0 * kPi * rng.uniform();
    for (size_t i = 0; i < ringing.size(); ++i) {
      const double t = double(i) / fs;
      ringing[i] += std::cos(2.0 * kPi * f * t + phase) * std::exp(-rate * t) * raised_cosine(t / kRingingRiseS);
    }
  }
  double energy = 0.0;
  for (double v : ringing) energy += v * v;
  const double scale = std::sqrt(own * std::pow(10.0, p.lf_ringing_db / 10.0) / energy);
  for (size_t i = 0; i < ringing.size(); ++i) rir.samples[peak + i] += float(scale * ringing[i]);
  record->ringing_energy_ratio_db = p.lf_ringing_db;
}

}  // namespace

void RirPerturbation::Register(OptionsItf* opts) {
  opts->Register("t60-scale", &t60_scale,
                 "Scale the RIR's T60 by this factor: the decay after the direct sound re-weighted by one exponential "
                 "envelope (1 = unchanged)");
  opts->Register("drr-offset-db", &drr_offset_db, "Scale the direct-sound window by this many dB (0 = unchanged)");
  opts->Register("lf-ringing-db", &lf_ringing_db,
                 "Add low-frequency modal ringing this many dB above the RIR's own energy below --lf-max-hz "
                 "(<= -100 = none)");
  opts->Register("lf-min-hz", &lf_min_hz, "Lowest ringing mode frequency (Hz)");
  opts->Register("lf-max-hz", &lf_max_hz, "Highest ringing mode frequency (Hz)");
  opts->Register("lf-t60", &lf_t60_s, "Decay time of the ringing modes (s)");
  opts->Register("direct-pre-ms", &direct_pre_ms, "Direct window before the peak (ms; rir-metrics' DRR window)");
  opts->Register("direct-post-ms", &direct_post_ms, "Direct window after the peak (ms)");
}

void RirPerturbation::validate() const {
  if (!(t60_scale > 0) || !std::isfinite(t60_scale)) throw Error("--t60-scale must be > 0");
  if (!std::isfinite(drr_offset_db) || std::fabs(drr_offset_db) > 40) throw Error("--drr-offset-db must be within +-40 dB");
  if (!std::isfinite(lf_ringing_db) || lf_ringing_db > 40) throw Error("--lf-ringing-db must be <= 40 dB");
  if (!(lf_min_hz > 0 && lf_max_hz > lf_min_hz)) throw Error("--lf-min-hz and --lf-max-hz must satisfy 0 < min < max");
  if (!(lf_t60_s > 0)) throw Error("--lf-t60 must be > 0");
  if (!(direct_pre_ms >= 0 && direct_post_ms >= 0)) throw Error("--direct-pre-ms and --direct-post-ms must be >= 0");
}

Signal perturb_rir(const Signal& rir, const RirPerturbation& p, std::uint64_t seed, PerturbationRecord* record) {
  PerturbationRecord unused;
  if (!record) record = &unused;
  *record = PerturbationRecord();
  record->t60_in_s = std::nan("");
  Signal out = rir;
  if (!p.changes_decay() && !p.changes_direct() && !p.adds_ringing()) return out;
  const RirMetrics m = measure_rir(rir);
  if (p.changes_decay()) scale_decay(out, p, m, record);
  if (p.changes_direct()) offset_direct(out, p, m.peak_sample);
  if (p.adds_ringing()) {
    if (p.lf_max_hz >= rir.sample_rate_hz / 2) throw Error("--lf-max-hz must lie below Nyquist");
    add_lf_ringing(out, p, m.peak_sample, seed, record);
  }
  return out;
}

}  // namespace tsrir
