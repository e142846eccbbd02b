#include "augment/noise_signal.h"

#include <algorithm>
#include <cmath>

#include "augment/reverb_steps.h"
#include "util/error.h"

namespace tsrir {

std::vector<float> nested_noise_signal(std::vector<float> noise, double sample_rate_hz, const PreparedRir* rir,
                                       double duration_s, bool noise_is_int16, bool kaldi_compat) {
  ReverbOptions nested;  // wav-reverberate's defaults: shifted, normalised
  nested.duration_s = static_cast<float>(duration_s);
  nested.kaldi_compat = kaldi_compat;
  std::vector<float> signal;
  if (!rir && !noise.empty()) {
    // Without an RIR the nested program's output is its input: normalisation scales by
    // sqrt(p / p) = 1 exactly (or 1 for silence), so only the tiling or cut to the duration is
    // left, which needs no powers (and only the first samples when cut).
    const size_t length = nested.duration_s > 0 ? kaldi_duration_samples(sample_rate_hz, nested.duration_s)
                                                : noise.size();
    if (length <= noise.size()) {
      noise.resize(length);
      signal = std::move(noise);
    } else {
      signal.resize(length);
      for (size_t done = 0; done < length;) {
        const size_t run = std::min(noise.size(), length - done);
        std::copy(noise.begin(), noise.begin() + static_cast<long>(run), signal.begin() + static_cast<long>(done));
        done += run;
      }
    }
    if (noise_is_int16) return signal;
  } else {
    signal = reverberate_channel(noise, sample_rate_hz, rir, {}, nested);
  }
  if (kaldi_compat) {
    kaldi_truncate_to_int16(&signal);
    return signal;
  }
  // The pipe's 16-bit WAV: encode_wav()'s rounding and clipping, read back as s / 32768 (the
  // equality with encode + decode is checked by InProcessNestedNoiseEqualsTheNestedPipe).
  for (float& v : signal) {
    if (!std::isfinite(v)) throw Error("nested noise signal: not a finite number");
    v = std::clamp(std::nearbyint(v * 32768.0f), -32768.0f, 32767.0f) / 32768.0f;
  }
  return signal;
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
  a.samples = std::make_shared<const std::vector<float>>(
      nested_noise_signal(*noise, sample_rate_hz, rir, planned.extend_to_s));
  return a;
}

}  // namespace tsrir
