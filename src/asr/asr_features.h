// Log-mel filterbank features for the CTC recogniser, computed with the toolkit's FFT engine
// (dsp/fft.h). The definition is spelled out here so that a test can re-derive it independently:
//   frames: length round(frame_length_ms * fs / 1000), shift round(frame_shift_ms * fs / 1000),
//           only whole frames (Kaldi's snip-edges), at least one frame;
//   each frame: DC removed (frame mean subtracted), pre-emphasis x[n] - a*x[n-1] (x[-1] = x[0]),
//           Hamming window 0.54 - 0.46 cos(2 pi n / (L - 1)), zero-padded to the next power of 2;
//   power spectrum |X(k)|^2, k = 0..N/2;
//   mel scale m(f) = 1127 ln(1 + f / 700); num_mel_bins triangles with edges equally spaced in mel
//           between low_hz and high_hz; bin k (frequency k fs / N) weighs
//           (m(f_k) - left) / (centre - left) on the rising and (right - m(f_k)) / (right - centre)
//           on the falling side, 0 outside;
//   feature = ln(max(sum_k w_k |X(k)|^2, 1e-10)).
// Per-utterance normalisation then gives each mel bin zero mean and unit variance over the
// utterance's frames (variance floored at 1e-8).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "util/options.h"

namespace tsrir {

struct LogMelOptions {
  double sample_rate_hz = 16000.0;  // audio is resampled to this rate when read
  double frame_length_ms = 25.0;
  double frame_shift_ms = 10.0;
  int num_mel_bins = 40;
  double low_hz = 20.0;
  double high_hz = 7600.0;          // <= 0: offset from Nyquist (Kaldi's convention)
  double preemphasis = 0.97;

  // Kaldi's names where Kaldi's compute-fbank-feats has the option (--num-mel-bins, --low-freq,
  // --high-freq, --frame-length, --frame-shift, --preemphasis-coefficient, --sample-frequency as
  // an alias of --sample-rate).
  void Register(OptionsItf* opts);
};

// Row-major [num_frames x num_mel_bins].
struct FeatureMatrix {
  size_t num_frames = 0;
  size_t num_bins = 0;
  std::vector<float> values;
  const float* row(size_t t) const { return values.data() + t * num_bins; }
};

// Throws Error when the signal is shorter than one frame or the options are inconsistent.
FeatureMatrix compute_log_mel(const std::vector<float>& samples, const LogMelOptions& options);
// In place: each column to zero mean and unit variance.
void normalise_mean_variance(FeatureMatrix* features);

}  // namespace tsrir
