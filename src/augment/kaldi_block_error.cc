#include "augment/kaldi_block_error.h"

#include <algorithm>

namespace tsrir {

size_t kaldi_block_fft_length(size_t filter_length) {
  size_t n = 1;
  while (n < 4 * filter_length) n *= 2;
  return n;
}

void add_kaldi_block_error(const std::vector<float>& x, const std::vector<float>& h, float* y, size_t y_length) {
  if (x.empty() || h.empty()) return;
  const size_t m = h.size();
  const size_t fft_length = kaldi_block_fft_length(m);
  const size_t block = fft_length - m + 1;
  const size_t output_length = x.size() + m - 1;
  // The filter's DC and Nyquist values (alternating sum; it is zero-padded to the FFT length).
  double h_dc = 0, h_nyquist = 0;
  for (size_t k = 0; k < m; ++k) {
    h_dc += h[k];
    h_nyquist += (k % 2 ? -1.0 : 1.0) * h[k];
  }
  const double inverse_length = 1.0 / static_cast<double>(fft_length);
  for (size_t start = 0; start < output_length; start += block) {
    // The block's input: the signal (zero past its end) over [start, start + its length).
    const size_t length = std::min(block, output_length - start);
    double x_dc = 0, x_nyquist = 0;
    const size_t stop = std::min(start + length, x.size());
    for (size_t i = start; i < stop; ++i) {
      x_dc += x[i];
      x_nyquist += ((i - start) % 2 ? -1.0 : 1.0) * x[i];
    }
    const double d = -h_nyquist * x_nyquist;
    const double n = h_dc * x_nyquist + h_nyquist * x_dc - h_nyquist * x_nyquist;
    const float even = static_cast<float>((d + n) * inverse_length);
    const float odd = static_cast<float>((d - n) * inverse_length);
    // All L outputs of the block land from its start on (the last M - 1 through Kaldi's temp_pad).
    const size_t end = std::min(start + fft_length, std::min(output_length, y_length));
    for (size_t i = start; i < end; ++i) y[i] += (i - start) % 2 ? odd : even;
  }
}

}  // namespace tsrir
