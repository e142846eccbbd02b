// Audio files in and out: libsndfile for decoding/encoding (WAV, FLAC, Ogg Vorbis, ... any rate,
// any channel count, int16/24/32/float), libsox's high-quality `rate` effect for resampling.
#pragma once
#include <string>
#include <vector>

#include "io/signal.h"

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
  std::string format;            // e.g. "WAV PCM_16"
};

// Reads an rxfilename (path, "-", or "cmd |"). Errors (each names the file and context): missing
// or unreadable file, truncated or unsupported data, zero-length audio, channel out of range,
// NaN/Inf samples.
Signal read_audio(const std::string& rx, const AudioReadOptions& options = {});
// All channels, de-interleaved: result[c][n].
std::vector<std::vector<float>> read_audio_channels(const std::string& rx, AudioInfo* info,
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
  std::string name_;
  void* file_ = nullptr;  // SNDFILE*
  AudioInfo info_;
  long long frames_read_ = 0;
};

enum class SampleFormat { kInt16, kFloat32 };
SampleFormat parse_sample_format(const std::string& name);  // "int16" | "float"

struct AudioWriteOptions {
  SampleFormat format = SampleFormat::kInt16;
  // int16: Kaldi's writer truncates toward zero and clips; we round to nearest and clip, and
  // report the clipped count through *clipped_samples when given.
  long long* clipped_samples = nullptr;
};

// Writes a mono WAV atomically (temp + rename). `path` "-" writes to stdout.
void write_wav(const std::string& path, const Signal& signal, const AudioWriteOptions& options = {});
// Multichannel: channels[c][n], all the same length.
void write_wav_channels(const std::string& path, const std::vector<std::vector<float>>& channels,
                        double sample_rate_hz, const AudioWriteOptions& options = {});
// Encodes to an in-memory WAV (for stdout and pipes).
std::vector<char> encode_wav(const std::vector<std::vector<float>>& channels, double sample_rate_hz,
                             const AudioWriteOptions& options = {});
// The same WAV in pieces, for audio too long to hold: the 44-byte header for `frames` frames
// (throws beyond 4 GB of data), then the samples, interleaved, appended block by block to *out
// with encode_wav()'s conversion (int16: rounded, clipped; clipped samples added to *clipped).
// `first_frame` only numbers a NaN/Inf frame in the error.
std::vector<char> wav_header(size_t frames, int channels, double sample_rate_hz, SampleFormat format);
void append_wav_frames(const float* interleaved, size_t frames, int channels, SampleFormat format,
                       long long first_frame, std::vector<char>* out, long long* clipped);

// libsox "rate -v" (very high quality, linear phase). Returns the input unchanged if rates match.
std::vector<float> resample(const std::vector<float>& samples, double from_hz, double to_hz);
Signal resample(const Signal& signal, double to_hz);

}  // namespace tsrir
