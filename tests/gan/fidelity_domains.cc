#include "fidelity_domains.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>

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

}  // namespace

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
    std::vector<double> x(n, 0.0);
    x[onset] = 1.0;
    for (size_t k = 0; k < n; ++k) x[k] += gain * reverb[k];

    if (s.hidden_effect) {
      r.effect = LowFrequencyEffect(1 + int(rng.below(kNumEffectKinds)));
      std::vector<double> effect(n, 0.0);
      if (r.effect == LowFrequencyEffect::kModes) {
        const int modes = 1 + int(rng.below(3));
        for (int m = 0; m < modes; ++m) {
          add_mode(effect, onset, fs, rng.uniform(50.0, 180.0), rng.uniform(0.0, 2 * M_PI),
                   rng.uniform(0.3, 1.0), rng.uniform(0.5, 1.0));
        }
      } else if (r.effect == LowFrequencyEffect::kModalCluster) {
        const int modes = 12 + int(rng.below(13));
        const double t60 = rng.uniform(0.2, 0.8);
        for (int m = 0; m < modes; ++m) {
          add_mode(effect, onset, fs, rng.uniform(40.0, 180.0), rng.uniform(0.0, 2 * M_PI),
                   t60 * rng.uniform(0.7, 1.3), rng.normal());
        }
      } else {
        const size_t at = onset + size_t(std::lround(rng.uniform(0.005, 0.040) * fs));
        add_mode(effect, std::min(at, n - 1), fs, rng.uniform(60.0, 160.0), rng.uniform(0.0, 2 * M_PI),
                 rng.uniform(0.4, 1.2), 1.0);
      }
      const double level_db = rng.uniform(s.effect_min_db, s.effect_max_db);
      const double effect_gain = std::sqrt(std::pow(10.0, level_db / 10.0) * energy(x) / energy(effect));
      for (size_t k = 0; k < n; ++k) x[k] += effect_gain * effect[k];
    }
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
