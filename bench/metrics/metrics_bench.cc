// In-process cost of measure_rir (no file I/O): all parameters, all bands, one core.
// Usage: metrics_bench [num_rirs=1000] [sample_rate_hz=16000] [duration_s=1.0]
//        metrics_bench generate <dir> <num_rirs>   (writes <dir>/<id>.wav and <dir>/rir.scp: 1 s,
//                                                  16 kHz, random T60 0.2-1.2 s, direct sound,
//                                                  noise floor -70..-50 dB)
#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "io/audio_io.h"
#include "metrics/rir_metrics.h"

namespace {

int generate(const std::string& dir, int count) {
  std::mt19937_64 gen(42);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uni;
  std::FILE* scp = std::fopen((dir + "/rir.scp").c_str(), "w");
  if (!scp) return 1;
  for (int k = 0; k < count; ++k) {
    char id[32];
    std::snprintf(id, sizeof id, "rir%05d", k);
    tsrir::Signal s;
    s.id = id;
    s.sample_rate_hz = 16000;
    s.samples.assign(16000, 0.0f);
    const double t60 = 0.2 + uni(gen);
    const size_t d = 40 + (size_t)(uni(gen) * 400);
    const double noise = std::pow(10.0, (-70 + 20 * uni(gen)) / 20) * 0.1;
    s.samples[d] = (float)(0.3 + 0.6 * uni(gen));
    for (size_t i = 0; i < s.samples.size(); ++i) {
      const double t = ((double)i - d) / 16000.0;
      const double tail = i > d + 3 ? 0.1 * std::pow(10.0, -3 * t / t60) * normal(gen) : 0.0;
      s.samples[i] += (float)(tail + noise * normal(gen));
    }
    const std::string path = dir + "/" + id + ".wav";
    tsrir::AudioWriteOptions o;
    o.format = tsrir::SampleFormat::kFloat32;
    tsrir::write_wav(path, s, o);
    std::fprintf(scp, "%s %s\n", id, path.c_str());
  }
  std::fclose(scp);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "generate") return generate(argv[2], std::atoi(argv[3]));
  const int n = argc > 1 ? std::atoi(argv[1]) : 1000;
  const double fs = argc > 2 ? std::atof(argv[2]) : 16000;
  const double seconds = argc > 3 ? std::atof(argv[3]) : 1.0;
  // A handful of distinct realistic RIRs (direct sound, exponential tail, noise floor) reused.
  std::vector<tsrir::Signal> rirs(16);
  std::mt19937_64 gen(1);
  std::normal_distribution<double> normal;
  for (size_t k = 0; k < rirs.size(); ++k) {
    tsrir::Signal& s = rirs[k];
    s.id = "rir" + std::to_string(k);
    s.sample_rate_hz = fs;
    s.samples.assign((size_t)(fs * seconds), 0.0f);
    const double t60 = 0.2 + 0.8 * k / rirs.size();
    const size_t d = (size_t)(0.005 * fs) + k * 7;
    s.samples[d] = 0.8f;
    for (size_t i = d + 5; i < s.samples.size(); ++i) {
      const double t = (i - d) / fs;
      s.samples[i] = (float)(0.05 * std::pow(10.0, -3 * t / t60) * normal(gen) + 1e-5 * normal(gen));
    }
  }
  // CPU time of this thread next to wall time: on a shared machine the wall clock also counts
  // time spent waiting for a core.
  auto cpu_ms = [] {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
  };
  std::printf("%-8s %6s %6s %8s %12s %12s\n", "def", "rate", "rirs", "dur_s", "wall_ms/rir", "cpu_ms/rir");
  for (tsrir::MetricsDefinition def : {tsrir::MetricsDefinition::kIso, tsrir::MetricsDefinition::kIrstats}) {
    tsrir::MetricsOptions o;
    o.definition = def;
    double sink = 0;
    tsrir::measure_rir(rirs[0], o);  // warm-up (filter design cache)
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_ms();
    for (int i = 0; i < n; ++i) sink += tsrir::measure_rir(rirs[i % rirs.size()], o).t60_s;
    const double cpu = cpu_ms() - c0;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-8s %6.0f %6d %8.2f %12.4f %12.4f   (mean T60 %.3f s)\n", tsrir::metrics_definition_name(def).c_str(),
                fs, n, seconds, ms / n, cpu / n, sink / n);
  }
  return 0;
}
