// FFTW3 single-precision real FFTs. Plans are created once per size (FFTW_ESTIMATE: planning a
// 2^20 transform with FFTW_MEASURE costs ~10 s) under a global lock, then shared by all threads
// through fftwf_execute_dft_r2c/c2r on per-call buffers. Power-of-two plans are looked up in wisdom
// made at build time (dsp/wisdom/fftw_wisdom_gen.cc): the same plans, without the search.
#pragma once
#include <complex>
#include <cstddef>
#include <vector>

namespace tsrir {

// Smallest n' >= n of the form 2^a 3^b 5^c with a >= 3 (fast for FFTW's real transforms); 1 for n <= 1.
size_t next_fast_fft_size(size_t n);

class RealFft {
 public:
  explicit RealFft(size_t n);
  size_t size() const { return n_; }
  size_t num_bins() const { return n_ / 2 + 1; }
  // in: n floats (fftwf_malloc-aligned or not: unaligned buffers use a copy); out: n/2+1 bins.
  void forward(const float* in, std::complex<float>* out) const;
  // Unnormalised inverse: forward then inverse multiplies by n.
  void inverse(const std::complex<float>* in, float* out) const;
  // The same values, using `in` as FFTW's work space (it is overwritten): one copy less per call,
  // for callers that recompute the spectrum each time.
  void inverse_in_place(std::complex<float>* in, float* out) const;

 private:
  size_t n_;
  void* plan_forward_;
  void* plan_inverse_;
};

// Spectrum of x zero-padded (or cropped) to n points.
std::vector<std::complex<float>> rfft(const std::vector<float>& x, size_t n);
// |X(k)|^2 for k in [0, n/2], x zero-padded to n.
std::vector<double> power_spectrum(const std::vector<float>& x, size_t n);

}  // namespace tsrir
