#include "augment/noise_signal.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace tsrir {

std::vector<float> nested_noise_signal(const std::vector<float>& noise, double sample_rate_hz, const PreparedRir* rir,
                                       double duration_s) {
  ReverbOptions nested;  // wav-reverberate's defaults: shifted, normalised
  nested.duration_s = duration_s;
  std::vector<float> signal = reverberate_channel(noise, sample_rate_hz, rir, {}, nested);
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
