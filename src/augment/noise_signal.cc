#include "augment/noise_signal.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "augment/reverb_steps.h"
#include "util/error.h"

namespace tsrir {
namespace {

// Without an RIR the nested program's output is its input: normalisation scales by sqrt(p / p) = 1
// exactly (or 1 for silence), so only the tiling or cut to the duration is left, which needs no
// powers (and only the first samples when cut). The length of that output:
size_t unreverberated_length(size_t noise_samples, double sample_rate_hz, double duration_s) {
  const float duration = static_cast<float>(duration_s);  // as ReverbOptions::duration_s holds it
  return duration > 0 ? kaldi_duration_samples(sample_rate_hz, duration) : noise_samples;
}

// The nested program's output through the pipe between the two programs: Kaldi's own truncation
// to 16 bits (kaldi_compat), else its 16-bit WAV: encode_wav()'s rounding and clipping, read back
// as s / 32768 (the equality with encode + decode is checked by
// InProcessNestedNoiseEqualsTheNestedPipe).
std::vector<float> through_the_pipe(std::vector<float> signal, bool kaldi_compat) {
  if (kaldi_compat) {
    kaldi_truncate_to_int16(&signal);
    return signal;
  }
  for (float& v : signal) {
    if (!std::isfinite(v)) throw Error("nested noise signal: not a finite number");
    v = std::clamp(std::nearbyint(v * 32768.0f), -32768.0f, 32767.0f) / 32768.0f;
  }
  return signal;
}

}  // namespace

std::vector<float> nested_noise_signal(const std::vector<float>& noise, double sample_rate_hz, const PreparedRir* rir,
                                       double duration_s, bool noise_is_int16, bool kaldi_compat) {
  if (rir || noise.empty()) {
    ReverbOptions nested;  // wav-reverberate's defaults: shifted, normalised
    nested.duration_s = static_cast<float>(duration_s);
    nested.kaldi_compat = kaldi_compat;
    return through_the_pipe(reverberate_channel(noise, sample_rate_hz, rir, {}, nested), kaldi_compat);
  }
  std::vector<float> signal(unreverberated_length(noise.size(), sample_rate_hz, duration_s));
  for (size_t done = 0; done < signal.size();) {
    const size_t run = std::min(noise.size(), signal.size() - done);
    std::copy(noise.begin(), noise.begin() + static_cast<long>(run), signal.begin() + static_cast<long>(done));
    done += run;
  }
  if (noise_is_int16) return signal;
  return through_the_pipe(std::move(signal), kaldi_compat);
}

std::vector<float> nested_noise_signal(std::vector<float>&& noise, double sample_rate_hz, const PreparedRir* rir,
                                       double duration_s, bool noise_is_int16, bool kaldi_compat) {
  // Kept or cut without an RIR: the buffer itself becomes the output, nothing is copied.
  if (!rir && !noise.empty()) {
    const size_t length = unreverberated_length(noise.size(), sample_rate_hz, duration_s);
    if (length <= noise.size()) {
      noise.resize(length);
      if (noise_is_int16) return std::move(noise);
      return through_the_pipe(std::move(noise), kaldi_compat);
    }
  }
  return nested_noise_signal(std::as_const(noise), sample_rate_hz, rir, duration_s, noise_is_int16, kaldi_compat);
}

AdditiveSignal planned_noise_signal(const PlannedNoise& planned, std::shared_ptr<const std::vector<float>> noise,
                                    const PreparedRir* rir, double sample_rate_hz) {
  AdditiveSignal a;
  a.snr_db = planned.snr_db;
  a.start_time_s = planned.start_time_s;
  a.offset_s = planned.offset_s;
  a.loop = planned.loop;
  if (!planned.needs_nested_reverberation()) {
    a.samples = std::move(noise);
    return a;
  }
  // *noise is the renderer's cached noise (shared): lent, so only the samples the result keeps are copied.
  a.samples = std::make_shared<const std::vector<float>>(
      nested_noise_signal(*noise, sample_rate_hz, rir, planned.extend_to_s));
  return a;
}

}  // namespace tsrir
