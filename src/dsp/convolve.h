// The toolkit's one convolution engine (simulate, eq, reverberate and diagnose all use it).
// Full linear convolution: y has length N + M - 1, y[n] = sum_k h[k] x[n-k].
#pragma once
#include <complex>
#include <functional>
#include <vector>

namespace tsrir {

// One-shot full convolution; picks a single FFT or overlap-save blocks by size, direct
// convolution for tiny filters. Accuracy: float rounding relative to the output peak.
std::vector<float> fft_convolve(const std::vector<float>& x, const std::vector<float>& h);

// A fixed filter (e.g. an RIR) applied to many signals: the filter spectrum is computed once.
// Overlap-save with FFT size ~4x the filter length; thread-safe for concurrent convolve() calls.
class Convolver {
 public:
  explicit Convolver(const std::vector<float>& h);
  size_t filter_length() const { return m_; }
  // Outputs per overlap-save block (0 for a tiny filter, convolved directly): a caller that feeds
  // pieces starting on multiples of it gets the same rounding as one whole-signal call.
  size_t block_length() const { return block_; }
  std::vector<float> convolve(const std::vector<float>& x) const;  // full, N + M - 1
  // The same values, delivered in order a block at a time without holding the whole output:
  // sink(first_index, values, count) for consecutive stretches covering [0, N + M - 1).
  void convolve_blocks(const std::vector<float>& x,
                       const std::function<void(size_t, const float*, size_t)>& sink) const;

 private:
  size_t m_, fft_size_, block_;
  std::vector<std::complex<float>> h_spectrum_;
  std::vector<float> h_direct_;  // used when the filter is tiny
};

// O(N*M) reference in double precision, for tests and tiny cases.
std::vector<double> direct_convolve(const std::vector<double>& x, const std::vector<double>& h);

}  // namespace tsrir
