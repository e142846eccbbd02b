#include "dsp/convolve.h"

#include <algorithm>

#include "dsp/fft.h"
#include "util/error.h"

namespace tsrir {
namespace {

// Below this many multiply-adds, direct convolution beats the FFT's fixed costs.
constexpr size_t kDirectWorkLimit = 4096 * 8;

// X[k] *= H[k] for every bin, as (a c - b d, a d + b c): what std::complex's operator*= computes
// for finite values, without its NaN-recovery branch (spectra of finite signals are finite).
void multiply_spectra(std::complex<float>* X, const std::complex<float>* H, size_t bins) {
  float* x = reinterpret_cast<float*>(X);
  const float* h = reinterpret_cast<const float*>(H);
  for (size_t k = 0; k < bins; ++k) {
    const float a = x[2 * k], b = x[2 * k + 1], c = h[2 * k], d = h[2 * k + 1];
    x[2 * k] = a * c - b * d;
    x[2 * k + 1] = a * d + b * c;
  }
}

std::vector<float> direct_float(const std::vector<float>& x, const std::vector<float>& h) {
  std::vector<float> y(x.size() + h.size() - 1, 0.0f);
  for (size_t k = 0; k < h.size(); ++k) {
    const float hk = h[k];
    if (hk == 0.0f) continue;
    float* out = y.data() + k;
    for (size_t n = 0; n < x.size(); ++n) out[n] += hk * x[n];
  }
  return y;
}

}  // namespace

std::vector<double> direct_convolve(const std::vector<double>& x, const std::vector<double>& h) {
  if (x.empty() || h.empty()) return {};
  std::vector<double> y(x.size() + h.size() - 1, 0.0);
  for (size_t k = 0; k < h.size(); ++k)
    for (size_t n = 0; n < x.size(); ++n) y[n + k] += h[k] * x[n];
  return y;
}

Convolver::Convolver(const std::vector<float>& h) : m_(h.size()) {
  if (h.empty()) throw Error("convolution with an empty filter");
  if (m_ <= 64) {
    h_direct_ = h;
    fft_size_ = block_ = 0;
    return;
  }
  // Overlap-save block: FFT ~4x the filter, as Kaldi does, so each block yields 3/4 useful output.
  // A power of two: FFTW plans those about twice as fast (4 ms vs 8 ms at 64k with FFTW_ESTIMATE),
  // which dominates a one-utterance pipe process.
  fft_size_ = 1;
  while (fft_size_ < 4 * m_) fft_size_ *= 2;
  block_ = fft_size_ - m_ + 1;
  h_spectrum_ = rfft(h, fft_size_);
}

std::vector<float> Convolver::convolve(const std::vector<float>& x) const {
  if (x.empty()) return {};
  if (!h_direct_.empty()) return direct_float(x, h_direct_);
  std::vector<float> y(x.size() + m_ - 1);
  convolve_blocks(x, [&y](size_t first, const float* values, size_t count) {
    std::copy(values, values + count, y.begin() + static_cast<long>(first));
  });
  return y;
}

void Convolver::convolve_blocks(const std::vector<float>& x,
                                const std::function<void(size_t, const float*, size_t)>& sink) const {
  if (x.empty()) return;
  if (!h_direct_.empty()) {
    const std::vector<float> y = direct_float(x, h_direct_);
    sink(0, y.data(), y.size());
    return;
  }
  const size_t out_len = x.size() + m_ - 1;
  const size_t n = fft_size_;
  RealFft fft(n);
  const float scale = 1.0f / static_cast<float>(n);
  std::vector<std::complex<float>> X(fft.num_bins());
  // The whole output fits one transform: no aliasing, one forward and one inverse FFT.
  if (out_len <= n) {
    std::vector<float> buf(n, 0.0f);
    std::copy(x.begin(), x.end(), buf.begin());
    fft.forward(buf.data(), X.data());
    multiply_spectra(X.data(), h_spectrum_.data(), X.size());
    fft.inverse_in_place(X.data(), buf.data());
    for (size_t i = 0; i < out_len; ++i) buf[i] *= scale;
    sink(0, buf.data(), out_len);
    return;
  }
  // Overlap-save: input segment j covers x[j*B - (M-1) .. j*B + B - 1]; the first M-1 outputs of
  // each circular convolution are aliased and dropped.
  std::vector<float> seg(n), res(n);
  for (size_t start = 0; start < out_len; start += block_) {
    // Segment begins M-1 samples before the output block start.
    const long long seg_start = static_cast<long long>(start) - static_cast<long long>(m_ - 1);
    // Copy the part of the segment that overlaps x; zeros before its start and after its end.
    const long long nx = static_cast<long long>(x.size());
    const long long lo = std::max<long long>(seg_start, 0);
    const long long hi = std::min<long long>(seg_start + static_cast<long long>(n), nx);
    std::fill(seg.begin(), seg.end(), 0.0f);
    if (hi > lo) std::copy(x.begin() + lo, x.begin() + hi, seg.begin() + (lo - seg_start));
    fft.forward(seg.data(), X.data());
    multiply_spectra(X.data(), h_spectrum_.data(), X.size());
    fft.inverse_in_place(X.data(), res.data());
    const size_t count = std::min(block_, out_len - start);
    float* out = res.data() + (m_ - 1);
    for (size_t i = 0; i < count; ++i) out[i] *= scale;
    sink(start, out, count);
  }
}

std::vector<float> fft_convolve(const std::vector<float>& x, const std::vector<float>& h) {
  if (x.empty() || h.empty()) return {};
  if (x.size() * h.size() <= kDirectWorkLimit) return direct_float(x, h);
  // The longer operand is the "signal": keeps the FFT size tied to the shorter one.
  const std::vector<float>& filt = h.size() <= x.size() ? h : x;
  const std::vector<float>& sig = h.size() <= x.size() ? x : h;
  return Convolver(filt).convolve(sig);
}

}  // namespace tsrir
