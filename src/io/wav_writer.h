// The toolkit's one WAV writer: every WAV it writes -- whole files, stdout, pipes and the streamed
// outputs of reverberate-data/wav-reverberate (augment/wav_sink.h) -- is wav_header() followed by
// append_wav_frames(). int16 is PCM with the 16-byte fmt chunk Kaldi's reader expects; float is
// WAVE_FORMAT_IEEE_FLOAT with the 18-byte fmt chunk (cbSize = 0) and a fact chunk, as sox writes it
// (libsndfile's 16-byte float fmt chunk makes sox warn "wave header missing extended part of fmt
// chunk").
#pragma once
#include <string>
#include <vector>

#include "io/signal.h"
#include "util/options.h"

namespace tsrir {

enum class SampleFormat { kInt16, kFloat32 };
const Choices<SampleFormat>& sample_format_choices();       // "int16" | "float"
SampleFormat parse_sample_format(const std::string& name);  // also "float32"

// How write_wav()/write_wav_channels() put a file at its path.
enum class WavFileMode {
  // Under a temporary name beside it, renamed when complete: the path never holds a partial WAV.
  kAtomic,
  // Straight to the path, no temporary name: only for a caller whose own staging directory is the
  // atomic unit (RirSetWriter, whose OwnedOutputDir staging dir is moved into place whole by
  // commit() and removed without it). A temporary name and a rename per file cost ~4 % of
  // rir-simulate's time (perf profile of 600 1 s RIRs, commit 908245f).
  kDirect,
};

struct AudioWriteOptions {
  SampleFormat format = SampleFormat::kInt16;
  // int16: Kaldi's writer truncates toward zero and clips; we round to nearest and clip, and
  // report the clipped count through *clipped_samples when given.
  long long* clipped_samples = nullptr;
  WavFileMode file_mode = WavFileMode::kAtomic;
};

// Writes a mono WAV, atomically unless options.file_mode says kDirect. `path` "-" writes to stdout.
void write_wav(const std::string& path, const Signal& signal, const AudioWriteOptions& options = {});
// Multichannel: channels[c][n], all the same length.
void write_wav_channels(const std::string& path, const std::vector<std::vector<float>>& channels,
                        double sample_rate_hz, const AudioWriteOptions& options = {});
// Encodes to an in-memory WAV (for stdout and pipes).
std::vector<char> encode_wav(const std::vector<std::vector<float>>& channels, double sample_rate_hz,
                             const AudioWriteOptions& options = {});
// The same WAV in pieces, for audio too long to hold: the header for `frames` frames (44 bytes for
// int16, 58 for float; throws beyond 4 GB of data), then the samples, interleaved, appended block by
// block to *out (int16: rounded, clipped; clipped samples added to *clipped). `first_frame` only
// numbers a NaN/Inf frame in the error.
std::vector<char> wav_header(size_t frames, int channels, double sample_rate_hz, SampleFormat format);
void append_wav_frames(const float* interleaved, size_t frames, int channels, SampleFormat format,
                       long long first_frame, std::vector<char>* out, long long* clipped);

}  // namespace tsrir
