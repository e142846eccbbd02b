// Audio files in: plain WAV (16/24/32-bit PCM, float) by io/wav_reader.h, everything else (FLAC,
// Ogg Vorbis, ... any rate, any channel count) by libsndfile, loaded when first needed
// (io/sndfile_api.h); resampling on request (io/resampler.h). Writing WAVs: io/wav_writer.h (both
// headers are included here for the callers of this one).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "io/resampler.h"
#include "io/signal.h"
#include "io/wav_writer.h"

namespace tsrir {

struct AudioReadOptions {
  int channel = 0;               // channel to keep; -1 = average of all channels
  double target_rate_hz = 0.0;   // > 0: resample to this rate
  std::string context;           // e.g. "wav.scp:12" for error messages
};

struct AudioInfo {
  double sample_rate_hz = 0.0;
  int channels = 0;
  long long frames = 0;
  std::string format;            // e.g. "WAV (Microsoft) Signed 16 bit PCM"
  bool int16_samples = false;    // 16-bit PCM: every sample is exactly s / 32768 for an integer s
};

// Reads an rxfilename (path, "-", or "cmd |"). Errors (each names the file and context): missing
// or unreadable file, truncated or unsupported data, zero-length audio, channel out of range,
// NaN/Inf samples.
Signal read_audio(const std::string& rx, const AudioReadOptions& options = {});
// All channels, de-interleaved: result[c][n].
std::vector<std::vector<float>> read_audio_channels(const std::string& rx, AudioInfo* info,
                                                    const std::string& context = "");
// The first `max_frames` frames of every channel (all of them when the file is shorter), for a
// caller that uses only a prefix; info->frames is still the whole length. A plain integer-PCM WAV
// file (io/wav_reader.h) is decoded only that far; any other input is decoded whole, so every check
// of a whole read still applies to it.
std::vector<std::vector<float>> read_audio_channels_prefix(const std::string& rx, size_t max_frames, AudioInfo* info,
                                                           const std::string& context = "");
// Decodes an in-memory file (used for pipes and stdin; also the fuzzing entry point).
std::vector<std::vector<float>> decode_audio_bytes(const std::vector<char>& bytes, AudioInfo* info,
                                                   const std::string& name);
AudioInfo probe_audio(const std::string& path);

// Reads an audio file (a path: it must be a seekable file, not a pipe) a block of frames at a
// time, so that its length does not decide the memory used. Same checks and messages as
// read_audio_channels(): a lying header or zero length when opened, NaN/Inf in each block, a
// shortfall against the header's frame count at the end. Errors name `context` and `shown_name`
// (default: the path; e.g. the pipe a temporary copy came from).
class AudioFileReader {
 public:
  explicit AudioFileReader(const std::string& path, const std::string& context = "",
                           const std::string& shown_name = "");
  ~AudioFileReader();
  const AudioInfo& info() const { return info_; }
  // Up to `max_frames` interleaved frames into *interleaved (resized to what was read); returns
  // the number of frames read, 0 at the end of the file.
  size_t read(std::vector<float>* interleaved, size_t max_frames);
  long long frames_read() const { return frames_read_; }
  AudioFileReader(const AudioFileReader&) = delete;
  AudioFileReader& operator=(const AudioFileReader&) = delete;

 private:
  struct SoundFile;  // the libsndfile handle (audio_io.cc)
  std::string name_;
  std::unique_ptr<SoundFile> file_;
  AudioInfo info_;
  long long frames_read_ = 0;
};

}  // namespace tsrir
