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

// libsox "rate -v" (very high quality, linear phase). Returns the input unchanged if rates match.
std::vector<float> resample(const std::vector<float>& samples, double from_hz, double to_hz);
Signal resample(const Signal& signal, double to_hz);

}  // namespace tsrir
