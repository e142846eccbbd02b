// A WAV output written as it is produced, for outputs too long to encode in memory: the header
// first (its sizes from the frame count known up front), then blocks of frames, with the same
// bytes as encode_wav() would give for the whole signal.
#pragma once
#include <cstdio>
#include <string>

#include "io/audio_io.h"

namespace tsrir {

class WavSink {
 public:
  // `wx`: "-" = stdout, "| command" = a pipe (bash), else a file written under a temporary name
  // and renamed by commit(). Throws (writing nothing) beyond the 4 GB a WAV can hold.
  WavSink(const std::string& wx, int channels, size_t frames, double sample_rate_hz, SampleFormat format);
  ~WavSink();  // without commit(): a file's temporary is removed, a pipe closed
  void write(const float* interleaved, size_t frames);
  // Checks that all frames came, flushes; renames a file into place, waits for a pipe's command.
  void commit();
  long long clipped_samples() const { return clipped_; }
  WavSink(const WavSink&) = delete;
  WavSink& operator=(const WavSink&) = delete;

 private:
  void put(const std::vector<char>& bytes);

  std::string target_, temp_path_;
  FILE* out_ = nullptr;
  bool is_pipe_ = false, committed_ = false;
  int channels_;
  size_t frames_, written_ = 0;
  SampleFormat format_;
  long long clipped_ = 0;
  std::vector<char> bytes_;
};

}  // namespace tsrir
