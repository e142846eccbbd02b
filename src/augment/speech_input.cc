#include "augment/speech_input.h"

#include "io/rxfile.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

constexpr double kPipeBytesPerSecond = 64000.0;

std::string name_of(const std::string& rx, const std::string& context) {
  return context.empty() ? rx : context + ": " + rx;
}

}  // namespace

SpeechInput open_speech_input(const std::string& rx, double max_in_memory_s, const std::string& temp_base,
                              const std::string& context) {
  SpeechInput input;
  input.rx = rx;
  const std::string t = trim(rx);
  if (t != "-" && !is_pipe_rxfilename(t)) {
    bool long_file = false;
    try {
      const AudioInfo info = probe_audio(rx);
      long_file = info.sample_rate_hz > 0 && static_cast<double>(info.frames) / info.sample_rate_hz > max_in_memory_s;
    } catch (const Error&) {
      // Unreadable: the in-memory reader below reports it with its usual message.
    }
    if (long_file) {
      input.path = rx;
    } else {
      input.channels = read_audio_channels(rx, &input.info, context);
    }
    return input;
  }

  // stdin or a pipe: held in memory up to the cap, then spilled to a temporary copy. A failing
  // command throws from stream_rxfile after its last block, before the copy is used.
  const double cap_bytes = max_in_memory_s * kPipeBytesPerSecond;
  std::vector<char> bytes;
  stream_rxfile(
      rx,
      [&](const char* data, size_t n) {
        if (!input.copy && static_cast<double>(bytes.size() + n) > cap_bytes) {
          input.copy = std::make_unique<TempFile>(temp_base);
          input.copy->append(bytes.data(), bytes.size());
          bytes.clear();
          bytes.shrink_to_fit();
        }
        if (input.copy) {
          input.copy->append(data, n);
        } else {
          bytes.insert(bytes.end(), data, data + n);
        }
      },
      context);
  if (input.copy) {
    input.path = input.copy->path();
  } else {
    input.channels = decode_audio_bytes(bytes, &input.info, name_of(rx, context));
  }
  return input;
}

}  // namespace tsrir
