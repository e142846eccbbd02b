// The options programs share, each declared once here (name, alias, help, check), so that
// --num-threads, --seed, --format and --overwrite mean the same in every program; --config and
// --help come with every command line (util/cli.h). A program's option struct keeps the fields its
// work reads and binds those it takes, at the place it registers them:
//   CommonOptions(opts).threads(&num_threads, "RIRs are rendered in parallel").seed(&seed, "the stochastic parts");
// and a program that writes directories binds --overwrite through its OutputPolicy
// (io/owned_output.h), which its main installs after parsing: no option writes a global.
//
// Defaults are the bound fields' initial values, by one rule: 1 thread (results and run time are
// then the same on any machine, and a shared machine is not taken over unasked) and seed 0;
// rir-diagnose alone starts at 2 threads and seed 1 (diagnose_options.h says why).
// Adding an option every program shares: a method here (declaration and definition), and a call
// where each program that takes it registers its options (docs/architecture.md).
#pragma once
#include <string>

#include "io/wav_writer.h"
#include "util/options.h"

namespace tsrir {

class CommonOptions {
 public:
  explicit CommonOptions(OptionsItf* opts) : opts_(opts) {}

  // --num-threads: at least 1; `what` says what runs in parallel (or what the threads serve).
  CommonOptions& threads(int* num_threads, const std::string& what);
  // --seed, also --random-seed (Kaldi's name): any integer in [-2^63, 2^64) (util/options.h);
  // `what` says what it seeds.
  CommonOptions& seed(Seed* seed, const std::string& what);
  // --format=int16|float: the sample format of the audio the program writes.
  CommonOptions& audio_format(SampleFormat* format);
  // --overwrite: write into an output directory tsrir did not write (io/owned_output.h).
  CommonOptions& overwrite(bool* overwrite);

 private:
  OptionsItf* opts_;
};

}  // namespace tsrir
