// wav-reverberate's Kaldi-syntax command line (src/augment/kaldi_options.h), including --config
// files. The input's lines are argv words; a line "--config" takes the rest of the input as the
// config file. Invariant: only Error escapes (no crash, no std::stoi-style exception), positionals
// come from the input.
#include <cmath>

#include "augment/kaldi_options.h"
#include "fuzz_common.h"
#include "util/strings.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string config = fuzz::scratch_path("options.conf");
  std::string text = fuzz::as_text(data, size);
  // --print-args would echo every input to stderr; the fuzzed words may still turn it back on.
  std::vector<std::string> args = {"wav-reverberate", "--print-args=false"};
  const size_t cut = text.find("\n--config\n");
  if (cut != std::string::npos) {
    fuzz::write_file(config, text.substr(cut + 10));
    text = text.substr(0, cut);
    args.push_back("--config=" + config);
  }
  for (const auto& w : split(text, '\n')) args.push_back(w);
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  fuzz::expect_only_errors([&] {
    KaldiOptionParser p("usage: wav-reverberate [options] <in> <out>\ne.g.: wav-reverberate a.wav b.wav");
    bool shift = false;
    int channel = -1;
    float volume = 0.0f;
    double snr = 0.0;
    std::string rir;
    p.Register("shift-output", &shift, "b");
    p.Register("input-channel", &channel, "i");
    p.Register("volume", &volume, "f");
    p.Register("snrs", &snr, "d");
    p.Register("impulse-response", &rir, "s");
    p.parse(static_cast<int>(argv.size()), argv.data());
    for (const auto& pos : p.positionals()) FUZZ_CHECK(pos.size() <= text.size(), "positional longer than input");
  });
  return 0;
}
