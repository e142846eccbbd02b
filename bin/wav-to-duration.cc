// wav-to-duration: drop-in for Kaldi's featbin/wav-to-duration (same name, options and output).
#include <iostream>
#include <limits>

#include "augment/kaldi_options.h"
#include "augment/wav_duration.h"
#include "util/cli.h"

namespace {

const char* kUsage =
    "Read wav files and output an archive consisting of a single float:\n"
    "the duration of each one in seconds. tsrir's drop-in for Kaldi's wav-to-duration, which\n"
    "Kaldi's utils/data/get_reco2dur.sh and steps/data/reverberate_data_dir.py call through PATH.\n"
    "Usage:  wav-to-duration [options...] <wav-rspecifier> <duration-wspecifier>\n"
    "e.g.\n"
    "  wav-to-duration scp:data/train/wav.scp ark,t:-\n"
    "  wav-to-duration --read-entire-file=true scp:data/train/wav.scp ark,t:data/train/reco2dur\n"
    "\n"
    "Input: scp:<wav.scp> whose entries are files, '-' or pipes ('<command> |'); any format\n"
    "libsndfile reads (Kaldi: 16-bit WAV only). Files are measured from their header; pipes are\n"
    "read to the end (Kaldi reads only their header), so a streamed WAV from a pipe gets its true\n"
    "duration instead of an error.\n"
    "Output: Kaldi's float archive, 'ark,t:' text lines '<key> <seconds> ' (7 significant digits)\n"
    "or 'ark:' binary; a file is written under a temporary name and renamed when complete.\n"
    "Exit status (Kaldi's): 0 when at least one duration was written, 1 when none (or wrong\n"
    "arguments), 255 on an error, which names the scp line.\n";

}  // namespace

int main(int argc, char** argv) {
  bool read_entire_file = false;
  auto define = [&](tsrir::KaldiOptionParser& po) {
    po.add("read-entire-file", &read_entire_file,
           "If true, decode every recording completely instead of reading file headers");
  };
  return tsrir::run_kaldi_program("wav-to-duration", kUsage, argc, argv, 2, define,
                                  [&](const std::vector<std::string>& args) {
    const std::vector<tsrir::RecordingDuration> durations = tsrir::wav_durations(args[0], read_entire_file);
    tsrir::write_duration_archive(args[1], durations);
    double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (const auto& d : durations) {
      sum += d.duration_s;
      lo = std::min<double>(lo, d.duration_s);
      hi = std::max<double>(hi, d.duration_s);
    }
    const size_t done = durations.size();
    tsrir::log_info("Printed duration for " + std::to_string(done) + " audio files.");
    if (done > 0)
      tsrir::log_info("Mean duration was " + std::to_string(sum / done) + ", min and max durations were " +
                      std::to_string(lo) + ", " + std::to_string(hi));
    return done != 0 ? 0 : 1;  // Kaldi: 1 when nothing was written
  });
}
