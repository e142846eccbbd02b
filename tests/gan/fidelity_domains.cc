#include "fidelity_domains.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>

#include "fidelity_filters.h"
#include "io/audio_io.h"
#include "util/rng.h"

namespace tsrir_test {
namespace {

double energy(const std::vector<double>& x) {
  double e = 0;
  for (double v : x) e += v * v;
  return e;
}

// A decaying sinusoid starting at sample `start` (amplitude 1 at its start).
void add_mode(std::vector<double>& out, size_t start, double fs, double hz, double phase, double t60_s,
              double amplitude) {
  const double decay = std::log(1000.0) / t60_s;
  for (size_t k = start; k < out.size(); ++k) {
    const double t = double(k - start) / fs;
    out[k] += amplitude * std::sin(2.0 * M_PI * hz * t + phase) * std::exp(-decay * t);
  }
}

// One of the three low-frequency kinds, drawn for this RIR, added to x at a level re x's energy.
LowFrequencyEffect add_low_frequency_effect(std::vector<double>& x, size_t onset, double fs,
                                            const FidelityDomainSpec& s, tsrir::Rng& rng) {
  const size_t n = x.size();
  const LowFrequencyEffect kind = LowFrequencyEffect(1 + int(rng.below(kNumLowFrequencyKinds)));
  std::vector<double> effect(n, 0.0);
  if (kind == LowFrequencyEffect::kModes) {
    const int modes = 1 + int(rng.below(3));
    for (int m = 0; m < modes; ++m) {
      add_mode(effect, onset, fs, rng.uniform(50.0, 180.0), rng.uniform(0.0, 2 * M_PI), rng.uniform(0.3, 1.0),
               rng.uniform(0.5, 1.0));
    }
  } else if (kind == LowFrequencyEffect::kModalCluster) {
    const int modes = 12 + int(rng.below(13));
    const double t60 = rng.uniform(0.2, 0.8);
    for (int m = 0; m < modes; ++m) {
      add_mode(effect, onset, fs, rng.uniform(40.0, 180.0), rng.uniform(0.0, 2 * M_PI), t60 * rng.uniform(0.7, 1.3),
               rng.normal());
    }
  } else {
    const size_t at = onset + size_t(std::lround(rng.uniform(0.005, 0.040) * fs));
    add_mode(effect, std::min(at, n - 1), fs, rng.uniform(60.0, 160.0), rng.uniform(0.0, 2 * M_PI),
             rng.uniform(0.4, 1.2), 1.0);
  }
  const double level_db = rng.uniform(s.effect_min_db, s.effect_max_db);
  const double effect_gain = std::sqrt(std::pow(10.0, level_db / 10.0) * energy(x) / energy(effect));
  for (size_t k = 0; k < n; ++k) x[k] += effect_gain * effect[k];
  return kind;
}

// x's part above `crossover_hz` multiplied by gain(sample); the rest of x unchanged. The part is
// the zero-phase high-pass's where the gain may go to zero (a decay: the causal high-pass's phase
// would leave part of the band however low the gain; the gains are 1 before the onset, so nothing
// comes before it), the causal high-pass's for a gain on the direct impulse (a shelf; the
// zero-phase part would ring before the direct sound).
template <typename Gain>
void scale_above(std::vector<double>& x, double crossover_hz, double fs, bool causal, Gain gain) {
  const std::vector<double> high = causal ? above(x, crossover_hz, fs) : zero_phase(x, crossover_hz, fs, true);
  for (size_t k = 0; k < x.size(); ++k) x[k] += (gain(k) - 1.0) * high[k];
}

// The kind's effect above the crossover, on the direct impulse or the reverberant part (kept
// apart until then).
void add_high_frequency_effect(std::vector<double>& direct, std::vector<double>& reverb, size_t onset, double fs,
                                double t60_s, const FidelityDomainSpec& s, tsrir::Rng& rng, FidelityRir& r) {
  const HiddenEffect kind = s.effect;
  if (kind == HiddenEffect::kDecay) {
    const double crossover = rng.uniform(s.crossover_min_hz, s.crossover_max_hz);
    const double start = rng.uniform(s.decay_start_min_s, s.decay_start_max_s);
    r.decay_speedup = rng.uniform(s.decay_speedup_min, s.decay_speedup_max);
    // From `start` on, the band decays decay_speedup times as fast as the RIR's T60 says.
    const double extra_per_s = (r.decay_speedup - 1.0) * std::log(1000.0) / t60_s;
    scale_above(reverb, crossover, fs, false, [&](size_t k) {
      const double t = (double(k) - double(onset)) / fs - start;
      return t > 0 ? std::exp(-extra_per_s * t) : 1.0;
    });
  }
  if (kind == HiddenEffect::kDirect) {
    const double crossover = rng.uniform(s.crossover_min_hz, s.crossover_max_hz);
    r.direct_db = rng.uniform(s.direct_min_db, s.direct_max_db);
    const double gain = std::pow(10.0, r.direct_db / 20.0);
    scale_above(direct, crossover, fs, true, [&](size_t) { return gain; });
  }
  if (kind == HiddenEffect::kEarly) {
    const double crossover = rng.uniform(s.crossover_min_hz, s.crossover_max_hz);
    r.early_db = rng.uniform(s.early_min_db, s.early_max_db);
    const double until = rng.uniform(s.early_min_s, s.early_max_s), fade = 0.010;
    const double gain = std::pow(10.0, r.early_db / 20.0);
    // Full gain up to `until - fade` after the onset, a raised-cosine fade to 1 at `until`.
    scale_above(reverb, crossover, fs, false, [&](size_t k) {
      const double t = (double(k) - double(onset)) / fs;
      if (t < 0) return 1.0;
      if (t <= until - fade) return gain;
      if (t >= until) return 1.0;
      const double w = 0.5 + 0.5 * std::cos(M_PI * (t - (until - fade)) / fade);
      return 1.0 + (gain - 1.0) * w;
    });
  }
}

}  // namespace

const char* hidden_effect_name(HiddenEffect kind) {
  switch (kind) {
    case HiddenEffect::kLowFrequency: return "low-frequency";
    case HiddenEffect::kDecay: return "decay";
    case HiddenEffect::kDirect: return "direct";
    case HiddenEffect::kEarly: return "early";
  }
  return "?";
}

bool parse_hidden_effect(const std::string& name, HiddenEffect* kind) {
  for (int k = 0; k < kNumHiddenEffects; ++k) {
    if (name == hidden_effect_name(HiddenEffect(k))) {
      *kind = HiddenEffect(k);
      return true;
    }
  }
  return false;
}

const char* effect_name(LowFrequencyEffect kind) {
  switch (kind) {
    case LowFrequencyEffect::kNone: return "none";
    case LowFrequencyEffect::kModes: return "modes";
    case LowFrequencyEffect::kModalCluster: return "modal-cluster";
    case LowFrequencyEffect::kDelayedBoom: return "delayed-boom";
  }
  return "?";
}

std::vector<FidelityRir> make_fidelity_domain(const FidelityDomainSpec& s, const std::string& name,
                                              int count, uint64_t seed) {
  std::vector<FidelityRir> rirs;
  const double fs = s.sample_rate_hz;
  const size_t n = size_t(std::lround(s.length_s * fs));
  for (int i = 0; i < count; ++i) {
    FidelityRir r;
    r.signal.id = name + "_" + std::to_string(i);
    r.signal.sample_rate_hz = fs;
    tsrir::Rng rng = tsrir::Rng::for_item(seed, r.signal.id);
    r.onset_s = rng.uniform(s.onset_min_s, s.onset_max_s);
    r.t60_s = std::exp(rng.uniform(std::log(s.t60_min_s), std::log(s.t60_max_s)));
    r.drr_db = rng.uniform(s.drr_min_db, s.drr_max_db);
    const size_t onset = size_t(std::lround(r.onset_s * fs));

    // Reverberant part: 3-8 discrete reflections 1-40 ms after the direct sound, then a decaying
    // white-noise tail from 2 ms on; scaled as a whole to the drawn DRR (direct energy 1).
    // Reflections stand 2-5 tail standard deviations above the tail at their time.
    std::vector<double> reverb(n, 0.0);
    const double decay = std::log(1000.0) / r.t60_s;
    const int reflections = 3 + int(rng.below(6));
    for (int j = 0; j < reflections; ++j) {
      const double t = rng.uniform(0.001, 0.040);
      const size_t at = onset + size_t(std::lround(t * fs));
      if (at < n) reverb[at] += (rng.uniform() < 0.5 ? -1.0 : 1.0) * 0.05 * rng.uniform(2.0, 5.0) * std::exp(-decay * t);
    }
    const double ramp_s = 0.002;
    for (size_t k = onset + 1; k < n; ++k) {
      const double t = double(k - onset) / fs;
      const double ramp = std::min(1.0, t / ramp_s);
      reverb[k] += 0.05 * ramp * rng.normal() * std::exp(-decay * t);
    }
    const double gain = std::sqrt(std::pow(10.0, -r.drr_db / 10.0) / energy(reverb));
    for (double& v : reverb) v *= gain;
    std::vector<double> direct(n, 0.0);
    direct[onset] = 1.0;

    // The hidden effect, drawn after everything above (so the acoustics do not depend on it).
    const bool low = s.effect == HiddenEffect::kLowFrequency;
    if (s.hidden_effect && !low) add_high_frequency_effect(direct, reverb, onset, fs, r.t60_s, s, rng, r);
    std::vector<double> x(n, 0.0);
    for (size_t k = 0; k < n; ++k) x[k] = direct[k] + reverb[k];
    if (s.hidden_effect && low) r.effect = add_low_frequency_effect(x, onset, fs, s, rng);
    r.signal.samples.resize(n);
    for (size_t k = 0; k < n; ++k) r.signal.samples[k] = float(x[k]);
    rirs.push_back(std::move(r));
  }
  return rirs;
}

std::string write_fidelity_domain(const std::vector<FidelityRir>& rirs, const std::string& dir) {
  std::filesystem::create_directories(dir);
  const std::string scp = dir + "/rir.scp";
  std::ofstream out(scp);
  tsrir::AudioWriteOptions options;
  options.format = tsrir::SampleFormat::kFloat32;
  for (const auto& r : rirs) {
    const std::string path = dir + "/" + r.signal.id + ".wav";
    tsrir::write_wav(path, r.signal, options);
    out << r.signal.id << ' ' << path << '\n';
  }
  return scp;
}

}  // namespace tsrir_test
