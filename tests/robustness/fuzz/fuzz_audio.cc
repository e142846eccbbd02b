// Audio decoding (every wav/flac/... the toolkit reads goes through libsndfile via the same
// read_all path; decode_audio_bytes is its in-memory entry point). Invariants: a decoded file has
// info.channels channels of equal, non-zero length with finite samples, at least info.frames
// frames (a shorter file must be an error: "truncated"); re-encoded as float WAV it decodes to the
// same samples bit for bit; resampling to 16 kHz gives the expected length and finite samples.
#include <cmath>

#include "fuzz_common.h"
#include "io/audio_io.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<char> bytes(data, data + size);
  fuzz::expect_only_errors([&] {
    AudioInfo info;
    auto channels = decode_audio_bytes(bytes, &info, "fuzz.wav");
    FUZZ_CHECK(!channels.empty() && static_cast<int>(channels.size()) == info.channels, info.format);
    const size_t frames = channels[0].size();
    FUZZ_CHECK(frames > 0 && static_cast<long long>(frames) >= info.frames, info.format);
    for (const auto& c : channels) {
      FUZZ_CHECK(c.size() == frames, "channels differ in length");
      for (float v : c) FUZZ_CHECK(std::isfinite(v), "non-finite sample");
    }
    // Everything below allocates in proportion to the decoded size; keep each input cheap.
    if (frames * channels.size() > (1u << 20)) return;
    if (info.sample_rate_hz >= 1.0 && info.sample_rate_hz <= 4294967295.0) {
      AudioWriteOptions w;
      w.format = SampleFormat::kFloat32;
      AudioInfo back_info;
      auto back = decode_audio_bytes(encode_wav(channels, info.sample_rate_hz, w), &back_info, "re-encoded");
      FUZZ_CHECK(back == channels, "float WAV round trip changed samples");
      FUZZ_CHECK(back_info.sample_rate_hz == std::round(info.sample_rate_hz), "round trip changed the rate");
    }
    // Resampling where the output stays small (a 1 Hz file claiming to be speech would otherwise
    // ask for 16000 outputs per input sample; that limit is the callers' concern, tested elsewhere).
    const double ratio = 16000.0 / info.sample_rate_hz;
    if (info.sample_rate_hz > 0 && ratio * frames < (1u << 20) && ratio < 64 && ratio > 1.0 / 64) {
      auto y = resample(channels[0], info.sample_rate_hz, 16000.0);
      FUZZ_CHECK(y.size() == static_cast<size_t>(std::llround(frames * ratio)), "resampled length");
      for (float v : y) FUZZ_CHECK(std::isfinite(v), "non-finite resampled sample");
    }
  });
  return 0;
}
