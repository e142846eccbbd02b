// wav-to-duration: Kaldi's featbin/wav-to-duration contract (what utils/data/get_reco2dur.sh and
// reverberate_data_dir.py call): durations of the recordings of a wav.scp written as a Kaldi float
// archive, text ("ark,t:") or binary ("ark:").
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "util/options.h"

namespace tsrir {

struct KaldiSpecifier {
  std::string type;                 // "scp" | "ark"
  std::vector<std::string> flags;   // e.g. "t", "p", "s", "cs"
  std::string target;               // file, "-" or "... |" / "| ..."
  bool has(const std::string& flag) const;
};
// "scp,p:wav.scp", "ark,t:-": throws Error naming the specifier when malformed.
KaldiSpecifier parse_kaldi_specifier(const std::string& text, const std::string& what);

struct RecordingDuration {
  std::string key;
  float duration_s = 0.0f;   // samples / rate, in single precision as Kaldi's BaseFloat
};

// What the start of a WAV stream says: rate, channels and, when the header states the data size
// (as Kaldi's WaveInfoHolder reads it), the duration. nullopt for another format or too few bytes;
// duration_s nullopt for a streamed header (size 0 or 0xFFFFFFFF). `bytes` = the first bytes of
// the stream (the header fits in 64 KB).
struct WavHeaderInfo {
  double sample_rate_hz = 0;
  int channels = 0;
  std::optional<double> duration_s;
};
std::optional<WavHeaderInfo> wav_header_info(const std::vector<char>& bytes);
std::optional<double> wav_header_duration_s(const std::vector<char>& bytes);  // wav_header_info's duration

// Duration, rate and channels of an rxfilename: a file from its header (libsndfile: any format); a
// pipe or "-" from its WAV header when that states the size, else by decoding it. A pipe is always
// read to its end (its output past the header discarded) and its exit status checked: a command
// stopped early dies of SIGPIPE, and some say so on stderr (flac: "ERROR, decoded number of
// samples is smaller than the total number of samples set in the STREAMINFO"). `read_entire_file`:
// always decode to the end.
struct RxAudioHeader {
  double duration_s = 0;
  double sample_rate_hz = 0;
  int channels = 0;
};
RxAudioHeader rx_audio_header(const std::string& rx, bool read_entire_file, const std::string& where);
double rx_duration_s(const std::string& rx, bool read_entire_file, const std::string& where);

// wav-to-duration's options (Kaldi's).
struct WavDurationOptions {
  bool read_entire_file = false;  // decode every recording to the end instead of reading headers
  void Register(OptionsItf* opts);
};

// Reads the scp (a wav.scp; "scp:" rspecifier only, as Kaldi's WaveHolder tables through scp).
// Files: from the header (as Kaldi's WaveInfoHolder); pipes and "-": the whole stream is read.
// With `read_entire_file` every recording is decoded completely. Errors name the scp line.
std::vector<RecordingDuration> wav_durations(const std::string& rspecifier, bool read_entire_file);

// Kaldi's BaseFloatWriter output: text "key 1.234 \n" (precision 7, Kaldi's InitKaldiOutputStream),
// binary "key \0B\4<float32>". Written to the wspecifier's file (atomically), stdout or a pipe.
std::string format_duration_archive(const std::vector<RecordingDuration>& durations, bool text);
void write_duration_archive(const std::string& wspecifier, const std::vector<RecordingDuration>& durations);

// The wav-to-duration program: durations of `rspecifier`'s recordings written to `wspecifier`, and
// Kaldi's summary log lines. Returns Kaldi's exit status: 0 when at least one was written, else 1.
int run_wav_to_duration(const WavDurationOptions& options, const std::string& rspecifier,
                        const std::string& wspecifier);

}  // namespace tsrir
