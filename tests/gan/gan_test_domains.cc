#include "gan_test_domains.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>

#include "io/audio_io.h"
#include "util/rng.h"

namespace tsrir_test {

std::vector<tsrir::Signal> make_domain(const DomainSpec& s, const std::string& name, int count,
                                       uint64_t seed) {
  std::vector<tsrir::Signal> rirs;
  const size_t n = size_t(std::lround(s.length_s * s.sample_rate_hz));
  for (int i = 0; i < count; ++i) {
    tsrir::Signal rir;
    rir.id = name + "_" + std::to_string(i);
    rir.sample_rate_hz = s.sample_rate_hz;
    rir.samples.assign(n, 0.0f);
    tsrir::Rng rng = tsrir::Rng::for_item(seed, rir.id);
    const size_t onset = size_t(std::lround(rng.uniform(s.onset_min_s, s.onset_max_s) * s.sample_rate_hz));
    const double t60 = rng.uniform(s.t60_min_s, s.t60_max_s);
    const double phase = s.random_mode_phase ? rng.uniform(0.0, 2.0 * M_PI) : 0.0;
    const double ln1000 = std::log(1000.0);
    rir.samples[onset] = 1.0f;
    for (size_t k = onset + 1; k < n; ++k) {
      const double t = double(k - onset) / s.sample_rate_hz;
      double v = s.tail_amplitude * rng.normal() * std::exp(-ln1000 * t / t60);
      if (s.mode_amplitude > 0) {
        v += s.mode_amplitude * std::sin(2.0 * M_PI * s.mode_hz * t + phase) * std::exp(-ln1000 * t / s.mode_decay_s);
      }
      rir.samples[k] = float(v);
    }
    rirs.push_back(std::move(rir));
  }
  return rirs;
}

std::string write_domain(const std::vector<tsrir::Signal>& rirs, const std::string& dir) {
  std::filesystem::create_directories(dir);
  const std::string scp = dir + "/rir.scp";
  std::ofstream out(scp);
  tsrir::AudioWriteOptions options;
  options.format = tsrir::SampleFormat::kFloat32;
  for (const auto& rir : rirs) {
    const std::string path = dir + "/" + rir.id + ".wav";
    tsrir::write_wav(path, rir, options);
    out << rir.id << ' ' << path << '\n';
  }
  return scp;
}

}  // namespace tsrir_test
