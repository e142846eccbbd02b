#include "dsp/fft.h"

#include <fftw3.h>

#include <cstring>
#include <map>
#include <memory>
#include <mutex>

#include "dsp/fft_plan_pair.h"
#include "util/error.h"

namespace tsrir {

// fftw_wisdom_data.cc, generated: wisdom per power-of-two size, ended by {0, nullptr}.
struct FftwWisdomEntry {
  size_t size;
  const char* wisdom;
};
extern const FftwWisdomEntry kFftwWisdom[];

namespace {

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
  // The build machine's wisdom for this size (dsp/wisdom/fftw_wisdom_gen.cc), if any: FFTW takes
  // all of the entry or, if it does not fit this FFTW or this CPU, none (the plan is then searched).
  for (const FftwWisdomEntry* w = kFftwWisdom; w->wisdom; ++w)
    if (w->size == n) fftwf_import_wisdom_from_string(w->wisdom);
  PlanPair p = make_plan_pair(n);
  if (!p.forward || !p.inverse) throw Error("FFTW: cannot plan a transform of size " + std::to_string(n));
  cache.emplace(n, p);
  return p;
}

// Per-thread SIMD-aligned scratch, grown on demand and kept: allocating fresh buffers per call
// made every large transform pay mmap, page faults and munmap (glibc serves >128 KiB from mmap).
struct Scratch {
  float* real = nullptr;
  fftwf_complex* bins = nullptr;
  size_t real_size = 0, bins_size = 0;
  ~Scratch() {
    fftwf_free(real);
    fftwf_free(bins);
  }
  float* reals(size_t n) {
    if (n > real_size) {
      fftwf_free(real);
      real = fftwf_alloc_real(n);
      if (!real) throw Error("FFTW: out of memory for a transform of size " + std::to_string(n));
      real_size = n;
    }
    return real;
  }
  fftwf_complex* complexes(size_t n) {
    if (n > bins_size) {
      fftwf_free(bins);
      bins = fftwf_alloc_complex(n);
      if (!bins) throw Error("FFTW: out of memory for a transform of size " + std::to_string(n));
      bins_size = n;
    }
    return bins;
  }
};
thread_local Scratch t_scratch;

// New-array execution needs the planning-time alignment (fftwf_alloc's, i.e. 0).
bool simd_aligned(const void* p) { return fftwf_alignment_of(static_cast<float*>(const_cast<void*>(p))) == 0; }

}  // namespace

size_t next_fast_fft_size(size_t n) {
  if (n <= 1) return 1;
  for (size_t m = n;; ++m) {
    // FFTW's real transforms want three factors of 2: with none (e.g. 16875 = 3^3 5^4) a transform
    // took 4x as long as one of 16000 or 17280 (ESTIMATE plans), with one (18750) 2x (bench/RESULTS.md).
    if (m % 8 != 0) continue;
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

// Aligned caller arrays are used in place; others go through the thread's scratch. r2c keeps
// its input (FFTW_PRESERVE_INPUT is the default for r2c), so a const input can be passed as is.
void RealFft::forward(const float* in, std::complex<float>* out) const {
  const size_t bins = n_ / 2 + 1;
  float* src = const_cast<float*>(in);
  if (!simd_aligned(in)) {
    src = t_scratch.reals(n_);
    std::memcpy(src, in, n_ * sizeof(float));
  }
  auto* dst = reinterpret_cast<fftwf_complex*>(out);
  const bool direct_out = simd_aligned(out);
  if (!direct_out) dst = t_scratch.complexes(bins);
  fftwf_execute_dft_r2c(static_cast<fftwf_plan>(plan_forward_), src, dst);
  if (!direct_out) std::memcpy(static_cast<void*>(out), dst, bins * sizeof(fftwf_complex));
}

// c2r destroys its input, so the caller's spectrum is always copied first.
void RealFft::inverse(const std::complex<float>* in, float* out) const {
  const size_t bins = n_ / 2 + 1;
  fftwf_complex* src = t_scratch.complexes(bins);
  std::memcpy(static_cast<void*>(src), static_cast<const void*>(in), bins * sizeof(fftwf_complex));
  float* dst = out;
  const bool direct_out = simd_aligned(out);
  if (!direct_out) dst = t_scratch.reals(n_);
  fftwf_execute_dft_c2r(static_cast<fftwf_plan>(plan_inverse_), src, dst);
  if (!direct_out) std::memcpy(out, dst, n_ * sizeof(float));
}

void RealFft::inverse_in_place(std::complex<float>* in, float* out) const {
  auto* src = reinterpret_cast<fftwf_complex*>(in);
  if (!simd_aligned(in)) {
    inverse(in, out);
    return;
  }
  float* dst = out;
  const bool direct_out = simd_aligned(out);
  if (!direct_out) dst = t_scratch.reals(n_);
  fftwf_execute_dft_c2r(static_cast<fftwf_plan>(plan_inverse_), src, dst);
  if (!direct_out) std::memcpy(out, dst, n_ * sizeof(float));
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
