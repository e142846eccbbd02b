// rir-eq speed: equalize 1,000 one-second 16 kHz RIRs (decaying noise with a direct impulse).
// Prints a table: the EQ alone (in memory: gains, FIR design + refinement, FFT filtering, output
// gains) on 1 and N threads, and `rir-eq apply`'s library path end to end (read wavs, EQ, write
// wavs + rir.scp + rir_list).
// Usage: eq_bench [num_rirs=1000] [threads=2]
#include <malloc.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <sys/resource.h>
#include <unistd.h>
#include <utility>
#include <vector>

#include "eq/eq_set.h"
#include "io/audio_io.h"
#include "util/parallel.h"
#include "util/rng.h"

using namespace tsrir;
using Clock = std::chrono::steady_clock;

namespace {

Signal make_rir(int i) {
  Rng rng(static_cast<uint64_t>(i) + 1);
  Signal s;
  s.id = "rir" + std::to_string(100000 + i);
  s.sample_rate_hz = 16000;
  s.samples.assign(16000, 0.0f);
  const double t60 = rng.uniform(0.3, 0.9);
  const size_t direct = static_cast<size_t>(rng.uniform(20, 400));
  for (size_t n = direct + 16; n < s.samples.size(); ++n) {
    s.samples[n] = static_cast<float>(0.05 * rng.normal() * std::exp(-6.9078 * (n - direct) / 16000.0 / t60));
  }
  s.samples[direct] = 0.9f;
  return s;
}

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// CPU seconds of this process (user + system): unlike wall time, not inflated by other jobs.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Timing {
  double wall_s, cpu_s;
};

}  // namespace

int main(int argc, char** argv) {
  mallopt(M_MMAP_MAX, 0);  // as bin/rir-eq.cc does
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  const int n = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  std::vector<Signal> rirs;
  for (int i = 0; i < n; ++i) rirs.push_back(make_rir(i));
  // A model like the hidden-effect test's: LF boost, HF roll-off, ~2 dB spread.
  EqModel model;
  model.sample_rate_hz = 16000;
  model.fitted_rirs = 100;
  GaussianComponent c;
  c.mean = Eigen::VectorXd(7);
  c.mean << 1.5, 4.0, 1.5, 0.3, -0.1, -1.0, -10.0;
  c.covariance = Eigen::MatrixXd::Zero(7, 7);
  c.covariance.diagonal() << 4, 3.5, 1.7, 0.8, 0.5, 0.8, 12;
  model.mixture.components.push_back(c);

  auto run_memory = [&](int num_threads) {
    std::vector<int> designs(n);
    const auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    parallel_for(n, num_threads, [&](size_t i) {
      Rng rng = Rng::for_item(1, rirs[i].id);
      EqApplyOptions o;
      o.measure_output = true;
      designs[i] = equalize_rir(rirs[i], draw_target_gains(model, rng), o).filters_designed;
    });
    const Timing t{seconds_since(t0), cpu_seconds() - c0};
    double mean_designs = 0;
    for (int d : designs) mean_designs += d / static_cast<double>(n);
    return std::make_pair(t, mean_designs);
  };
  run_memory(1);  // warm-up: FFTW plans, grid caches
  const auto one = run_memory(1);
  const auto many = run_memory(threads);

  const auto dir = std::filesystem::temp_directory_path() / ("tsrir_eq_bench_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "in");
  {
    std::ofstream scp(dir / "in.scp");
    for (const Signal& s : rirs) {
      const std::string wav = (dir / "in" / (s.id + ".wav")).string();
      write_wav(wav, s);
      scp << s.id << ' ' << wav << '\n';
    }
  }
  auto run_files = [&](int num_threads) {
    ApplySetOptions o;
    o.seed = 1;
    o.num_threads = num_threads;
    const auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    equalize_rir_set(model, (dir / "in.scp").string(), (dir / ("out" + std::to_string(num_threads))).string(), o);
    return Timing{seconds_since(t0), cpu_seconds() - c0};
  };
  const Timing files_one = run_files(1);
  const Timing files_many = run_files(threads);
  std::filesystem::remove_all(dir);

  std::printf("rir-eq apply: %d one-second 16 kHz RIRs, 2049-tap FIR, refine 3 (mean %.2f FIR designs per RIR)\n", n,
              one.second);
  std::printf("%-44s %8s %8s %8s %14s\n", "what", "threads", "wall_s", "cpu_s", "cpu_ms_per_rir");
  auto row = [&](const char* what, int t, const Timing& x) {
    std::printf("%-44s %8d %8.3f %8.3f %14.3f\n", what, t, x.wall_s, x.cpu_s, 1e3 * x.cpu_s / n);
  };
  row("EQ in memory (gains, design, filter, check)", 1, one.first);
  row("EQ in memory", threads, many.first);
  row("end to end: read wavs, EQ, write int16 set", 1, files_one);
  row("end to end", threads, files_many);
  std::printf("hardware threads: %u\n", std::thread::hardware_concurrency());
  return 0;
}
