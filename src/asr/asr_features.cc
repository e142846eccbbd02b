#include "asr/asr_features.h"

#include <cmath>
#include <complex>

#include "dsp/fft.h"
#include "util/error.h"

namespace tsrir {
namespace {

double mel(double hz) { return 1127.0 * std::log(1.0 + hz / 700.0); }

size_t next_power_of_two(size_t n) {
  size_t p = 1;
  while (p < n) p <<= 1;
  return p;
}

}  // namespace

FeatureMatrix compute_log_mel(const std::vector<float>& samples, const LogMelOptions& o) {
  const double fs = o.sample_rate_hz;
  const size_t length = size_t(std::lround(o.frame_length_ms * fs / 1000.0));
  const size_t shift = size_t(std::lround(o.frame_shift_ms * fs / 1000.0));
  const double high_hz = o.high_hz > 0 ? o.high_hz : fs / 2 + o.high_hz;
  if (length < 2 || shift < 1 || o.num_mel_bins < 1) throw Error("log-mel: bad frame length, shift or number of bins");
  if (!(o.low_hz >= 0 && high_hz > o.low_hz && high_hz <= fs / 2)) {
    throw Error("log-mel: need 0 <= low-hz < high-hz <= Nyquist");
  }
  if (samples.size() < length) {
    throw Error("log-mel: signal of " + std::to_string(samples.size()) + " samples is shorter than one frame (" +
                std::to_string(length) + ")");
  }
  const size_t n_fft = next_power_of_two(length);
  const size_t n_bins = n_fft / 2 + 1;
  const int M = o.num_mel_bins;

  // Filterbank as per-filter (first bin, weights) spans.
  const double mel_low = mel(o.low_hz), mel_high = mel(high_hz);
  const double delta = (mel_high - mel_low) / (M + 1);
  std::vector<size_t> first(M);
  std::vector<std::vector<float>> weights(M);
  for (int m = 0; m < M; ++m) {
    const double left = mel_low + m * delta, centre = left + delta, right = centre + delta;
    first[m] = 0;
    for (size_t k = 0; k < n_bins; ++k) {
      const double mk = mel(k * fs / n_fft);
      double w = 0.0;
      if (mk > left && mk <= centre) w = (mk - left) / (centre - left);
      else if (mk > centre && mk < right) w = (right - mk) / (right - centre);
      if (w > 0) {
        if (weights[m].empty()) first[m] = k;
        weights[m].resize(k - first[m] + 1, 0.0f);
        weights[m][k - first[m]] = float(w);
      }
    }
  }
  std::vector<float> window(length);
  for (size_t n = 0; n < length; ++n) window[n] = float(0.54 - 0.46 * std::cos(2 * M_PI * n / (length - 1)));

  FeatureMatrix out;
  out.num_frames = 1 + (samples.size() - length) / shift;
  out.num_bins = size_t(M);
  out.values.resize(out.num_frames * out.num_bins);
  RealFft fft(n_fft);
  std::vector<float> frame(n_fft, 0.0f);
  std::vector<std::complex<float>> spectrum(n_bins);
  std::vector<double> power(n_bins);
  for (size_t t = 0; t < out.num_frames; ++t) {
    const float* x = samples.data() + t * shift;
    double mean = 0.0;
    for (size_t n = 0; n < length; ++n) mean += x[n];
    mean /= length;
    for (size_t n = length; n-- > 0;) {
      const double prev = (n > 0 ? x[n - 1] : x[0]) - mean;
      frame[n] = float(((x[n] - mean) - o.preemphasis * prev) * window[n]);
    }
    fft.forward(frame.data(), spectrum.data());
    for (size_t k = 0; k < n_bins; ++k) power[k] = std::norm(std::complex<double>(spectrum[k]));
    float* row = out.values.data() + t * out.num_bins;
    for (int m = 0; m < M; ++m) {
      double e = 0.0;
      for (size_t j = 0; j < weights[m].size(); ++j) e += weights[m][j] * power[first[m] + j];
      row[m] = float(std::log(std::max(e, 1e-10)));
    }
  }
  return out;
}

void normalise_mean_variance(FeatureMatrix* f) {
  const size_t T = f->num_frames, D = f->num_bins;
  if (T == 0) return;
  for (size_t d = 0; d < D; ++d) {
    double sum = 0.0, sum2 = 0.0;
    for (size_t t = 0; t < T; ++t) sum += f->values[t * D + d];
    const double mean = sum / T;
    for (size_t t = 0; t < T; ++t) {
      const double v = f->values[t * D + d] - mean;
      sum2 += v * v;
    }
    const double scale = 1.0 / std::sqrt(std::max(sum2 / T, 1e-8));
    for (size_t t = 0; t < T; ++t) f->values[t * D + d] = float((f->values[t * D + d] - mean) * scale);
  }
}

}  // namespace tsrir
