#include "dsp/fft.h"

#include <fftw3.h>

#include <cstring>
#include <map>
#include <memory>
#include <mutex>

#include "util/error.h"

namespace tsrir {
namespace {

struct PlanPair {
  fftwf_plan forward;
  fftwf_plan inverse;
};

// FFTW's planner is not thread-safe; execution of an existing plan on new arrays is.
std::mutex g_plan_mutex;
std::map<size_t, PlanPair>& plan_cache() {
  static auto* cache = new std::map<size_t, PlanPair>();  // never freed: plans live for the process
  return *cache;
}

PlanPair get_plans(size_t n) {
  std::lock_guard<std::mutex> lock(g_plan_mutex);
  auto& cache = plan_cache();
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  float* in = fftwf_alloc_real(n);
  fftwf_complex* out = fftwf_alloc_complex(n / 2 + 1);
  PlanPair p;
  p.forward = fftwf_plan_dft_r2c_1d(static_cast<int>(n), in, out, FFTW_ESTIMATE);
  p.inverse = fftwf_plan_dft_c2r_1d(static_cast<int>(n), out, in, FFTW_ESTIMATE);
  fftwf_free(in);
  fftwf_free(out);
  if (!p.forward || !p.inverse) throw Error("FFTW: cannot plan a transform of size " + std::to_string(n));
  cache.emplace(n, p);
  return p;
}

struct AlignedFloats {
  explicit AlignedFloats(size_t n) : p(fftwf_alloc_real(n)) {}
  ~AlignedFloats() { fftwf_free(p); }
  float* p;
};
struct AlignedComplex {
  explicit AlignedComplex(size_t n) : p(fftwf_alloc_complex(n)) {}
  ~AlignedComplex() { fftwf_free(p); }
  fftwf_complex* p;
};

}  // namespace

size_t next_fast_fft_size(size_t n) {
  if (n <= 1) return 1;
  for (size_t m = n;; ++m) {
    size_t r = m;
    for (size_t f : {2, 3, 5})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

RealFft::RealFft(size_t n) : n_(n) {
  if (n < 1) throw Error("FFT size must be positive");
  PlanPair p = get_plans(n);
  plan_forward_ = p.forward;
  plan_inverse_ = p.inverse;
}

// New-array execution requires the same alignment as at planning time; fftwf_alloc gives SIMD
// alignment, so we always go through aligned scratch buffers.
void RealFft::forward(const float* in, std::complex<float>* out) const {
  AlignedFloats a(n_);
  AlignedComplex b(n_ / 2 + 1);
  std::memcpy(a.p, in, n_ * sizeof(float));
  fftwf_execute_dft_r2c(static_cast<fftwf_plan>(plan_forward_), a.p, b.p);
  std::memcpy(static_cast<void*>(out), b.p, (n_ / 2 + 1) * sizeof(fftwf_complex));
}

void RealFft::inverse(const std::complex<float>* in, float* out) const {
  AlignedComplex a(n_ / 2 + 1);
  AlignedFloats b(n_);
  std::memcpy(a.p, static_cast<const void*>(in), (n_ / 2 + 1) * sizeof(fftwf_complex));
  fftwf_execute_dft_c2r(static_cast<fftwf_plan>(plan_inverse_), a.p, b.p);
  std::memcpy(out, b.p, n_ * sizeof(float));
}

std::vector<std::complex<float>> rfft(const std::vector<float>& x, size_t n) {
  std::vector<float> padded(n, 0.0f);
  std::memcpy(padded.data(), x.data(), std::min(n, x.size()) * sizeof(float));
  RealFft fft(n);
  std::vector<std::complex<float>> out(fft.num_bins());
  fft.forward(padded.data(), out.data());
  return out;
}

std::vector<double> power_spectrum(const std::vector<float>& x, size_t n) {
  auto spec = rfft(x, n);
  std::vector<double> p(spec.size());
  for (size_t k = 0; k < spec.size(); ++k) p[k] = std::norm(std::complex<double>(spec[k]));
  return p;
}

}  // namespace tsrir
