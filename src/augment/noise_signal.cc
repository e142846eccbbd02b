#include "augment/noise_signal.h"

#include "io/audio_io.h"

namespace tsrir {

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
  ReverbOptions nested;  // wav-reverberate's defaults: shifted, normalised
  nested.duration_s = planned.extend_to_s;
  std::vector<float> signal = reverberate_channel(*noise, sample_rate_hz, rir, {}, nested);
  // Through the same 16-bit WAV encoding and decoding as the pipe.
  AudioInfo info;
  std::vector<std::vector<float>> decoded =
      decode_audio_bytes(encode_wav({signal}, sample_rate_hz), &info, "nested noise signal");
  a.samples = std::make_shared<const std::vector<float>>(std::move(decoded.at(0)));
  return a;
}

}  // namespace tsrir
