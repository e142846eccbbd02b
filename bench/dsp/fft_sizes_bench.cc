// Speed of the toolkit's real FFT (dsp/fft.h: FFTW, ESTIMATE plans) at every 2^a 3^b 5^c size in a
// range, to show which sizes next_fast_fft_size() may choose: one forward and one inverse transform
// per repetition, median of 7 runs of R repetitions, CPU time of this thread.
//   fft_sizes_bench [lo (15000)] [hi (20500)] [repetitions (200)]
// Prints: size, factors of 2 (a), microseconds per forward + inverse pair, ns / (n log2 n), and
// whether next_fast_fft_size() can return it.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "dsp/fft.h"

namespace {

double thread_cpu_s() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

bool five_smooth(size_t m) {
  for (size_t f : {2, 3, 5})
    while (m % f == 0) m /= f;
  return m == 1;
}

int twos(size_t m) {
  int a = 0;
  for (; m % 2 == 0; m /= 2) ++a;
  return a;
}

double pair_us(size_t n, int repetitions) {
  const tsrir::RealFft fft(n);
  std::vector<float> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = static_cast<float>(std::sin(0.37 * i) + 0.01 * (i % 17));
  std::vector<std::complex<float>> bins(fft.num_bins());
  std::vector<double> runs;
  for (int run = 0; run < 7; ++run) {
    const double t0 = thread_cpu_s();
    for (int r = 0; r < repetitions; ++r) {
      fft.forward(x.data(), bins.data());
      fft.inverse(bins.data(), x.data());
      x[0] *= 1.0f / static_cast<float>(n);  // keeps the values bounded
    }
    runs.push_back((thread_cpu_s() - t0) / repetitions);
  }
  std::nth_element(runs.begin(), runs.begin() + 3, runs.end());
  return runs[3] * 1e6;
}

}  // namespace

int main(int argc, char** argv) {
  const size_t lo = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 15000;
  const size_t hi = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 20500;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 200;
  std::printf("| size | factors of 2 | us per forward + inverse | ns / (n log2 n) | next_fast_fft_size may return it |\n");
  std::printf("|---|---|---|---|---|\n");
  for (size_t n = lo; n <= hi; ++n) {
    if (!five_smooth(n)) continue;
    const double us = pair_us(n, repetitions);
    std::printf("| %zu | %d | %.1f | %.3f | %s |\n", n, twos(n), us, 1e3 * us / (n * std::log2(double(n))),
                tsrir::next_fast_fft_size(n) == n ? "yes" : "no");
  }
  return 0;
}
