#include "augment/wav_sink.h"

#include <cerrno>
#include <cstring>

#include "io/atomic_output.h"
#include "io/shell.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

WavSink::WavSink(const std::string& wx, int channels, size_t frames, double sample_rate_hz, SampleFormat format)
    : target_(trim(wx)), channels_(channels), frames_(frames), format_(format) {
  const std::vector<char> header = wav_header(frames, channels, sample_rate_hz, format);
  if (target_ == "-") {
    out_ = stdout;
  } else if (starts_with(target_, "|")) {
    const std::string command = "/bin/bash -c " + shell_quote(trim(target_.substr(1)));
    out_ = popen(command.c_str(), "we");
    if (!out_) throw Error("cannot start output pipe '" + target_ + "'");
    is_pipe_ = true;
  } else {
    temp_path_ = make_temp_path(target_);
    out_ = std::fopen(temp_path_.c_str(), "wbe");
    if (!out_) {
      const std::string reason = std::strerror(errno);
      discard_temp_path(temp_path_);
      throw Error("cannot open " + target_ + " for writing: " + reason);
    }
  }
  put(header);
}

WavSink::~WavSink() {
  if (committed_) return;
  if (is_pipe_) {
    pclose(out_);
  } else if (!temp_path_.empty()) {
    if (out_) std::fclose(out_);
    discard_temp_path(temp_path_);
  }
}

void WavSink::put(const std::vector<char>& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), out_) != bytes.size())
    throw Error("write error on output '" + target_ + "': " + std::strerror(errno));
}

void WavSink::write(const float* interleaved, size_t frames) {
  if (written_ + frames > frames_) throw Error("output '" + target_ + "': more frames than its header announced");
  bytes_.clear();
  append_wav_frames(interleaved, frames, channels_, format_, static_cast<long long>(written_), &bytes_, &clipped_);
  put(bytes_);
  written_ += frames;
}

void WavSink::commit() {
  if (written_ != frames_)
    throw Error("output '" + target_ + "': " + std::to_string(written_) + " frames written, header announced " +
                std::to_string(frames_));
  const bool flushed = std::fflush(out_) == 0;
  if (is_pipe_) {
    const int status = pclose(out_);
    committed_ = true;
    if (!flushed) throw Error("write error on output '" + target_ + "'");
    if (status != 0) throw Error("output pipe '" + target_ + "' failed with status " + std::to_string(status));
    return;
  }
  if (temp_path_.empty()) {
    if (!flushed) throw Error("write error on output '" + target_ + "'");
    committed_ = true;
    return;
  }
  const bool closed = std::fclose(out_) == 0;
  out_ = nullptr;
  if (!flushed || !closed) {
    discard_temp_path(temp_path_);
    committed_ = true;
    throw Error("error writing " + target_);
  }
  commit_temp_path(temp_path_, target_);
  committed_ = true;
}

}  // namespace tsrir
