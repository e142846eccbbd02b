// wav-to-duration: drop-in for Kaldi's featbin/wav-to-duration (same name, options and output).
#include "augment/kaldi_options.h"
#include "augment/wav_duration.h"

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
    "read to the end (Kaldi stops them after the header, which cuts the command off: flac then\n"
    "prints an error), and a command that fails is an error; a streamed WAV from a pipe gets its\n"
    "true duration instead of an error.\n"
    "Output: Kaldi's float archive, 'ark,t:' text lines '<key> <seconds> ' (7 significant digits)\n"
    "or 'ark:' binary; a file is written under a temporary name and renamed when complete.\n"
    "Exit status: 0 when at least one duration was written, 1 when none, on wrong arguments and on\n"
    "an error, which names the scp line (Kaldi's binary exits 255 on an error).\n";

}  // namespace

int main(int argc, char** argv) {
  tsrir::WavDurationOptions options;
  auto define = [&](tsrir::KaldiOptionParser& po) { options.Register(&po); };
  return tsrir::run_kaldi_program("wav-to-duration", kUsage, argc, argv, 2, define,
                                  [&](const std::vector<std::string>& args) {
                                    return tsrir::run_wav_to_duration(options, args[0], args[1]);
                                  });
}
