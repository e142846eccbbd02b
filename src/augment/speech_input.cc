#include "augment/speech_input.h"

#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "io/rxfile.h"
#include "io/shell.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

constexpr double kPipeBytesPerSecond = 64000.0;

std::string name_of(const std::string& rx, const std::string& context) {
  return context.empty() ? rx : context + ": " + rx;
}

// stdin or a command's stdout, read in blocks; the command's stderr passes through to ours (it
// is not held, whatever its length).
class ByteStream {
 public:
  ByteStream(const std::string& rx, const std::string& context) : rx_(trim(rx)), context_(context) {
    if (rx_ == "-") {
      in_ = stdin;
      return;
    }
    command_ = trim(rx_.substr(0, rx_.size() - 1));
    if (command_.empty()) throw Error(name_of(rx, context) + ": empty pipe command");
    in_ = popen(("/bin/bash -c " + shell_quote(command_)).c_str(), "re");
    if (!in_) throw Error(name_of(rx, context) + ": cannot start command: " + std::strerror(errno));
  }
  ~ByteStream() {
    if (in_ && in_ != stdin) pclose(in_);
  }
  size_t read(char* buffer, size_t size) {
    const size_t n = std::fread(buffer, 1, size, in_);
    if (n == 0 && std::ferror(in_)) throw Error(name_of(rx_, context_) + ": read error: " + std::strerror(errno));
    return n;
  }
  // After the end of the stream: a failing command is an error, never a short input.
  void close() {
    if (in_ == stdin) return;
    const int status = pclose(in_);
    in_ = nullptr;
    const std::string what = (context_.empty() ? "" : context_ + ": ") + "command '" + command_ + "'";
    if (status == -1) throw Error(what + ": cannot get its exit status");
    if (WIFSIGNALED(status)) throw Error(what + " was killed by signal " + std::to_string(WTERMSIG(status)));
    if (WEXITSTATUS(status) != 0) throw Error(what + " failed with exit status " + std::to_string(WEXITSTATUS(status)));
  }

 private:
  std::string rx_, context_, command_;
  FILE* in_ = nullptr;
};

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

  const double cap_bytes = max_in_memory_s * kPipeBytesPerSecond;
  std::vector<char> bytes;
  ByteStream stream(rx, context);
  std::vector<char> block(1 << 16);
  for (size_t n; (n = stream.read(block.data(), block.size())) > 0;) {
    if (!input.copy && static_cast<double>(bytes.size() + n) > cap_bytes) {
      input.copy = std::make_unique<TempFile>(temp_base);
      input.copy->append(bytes.data(), bytes.size());
      bytes.clear();
      bytes.shrink_to_fit();
    }
    if (input.copy) {
      input.copy->append(block.data(), n);
    } else {
      bytes.insert(bytes.end(), block.data(), block.data() + n);
    }
  }
  stream.close();
  if (input.copy) {
    input.path = input.copy->path();
  } else {
    input.channels = decode_audio_bytes(bytes, &input.info, name_of(rx, context));
  }
  return input;
}

}  // namespace tsrir
