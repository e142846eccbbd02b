// Simulating a whole room list into a Kaldi-ready RIR set (what rir-simulate does).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/audio_io.h"
#include "sim/room.h"
#include "util/options.h"

namespace tsrir::sim {

struct SimulateOptions {
  double sample_rate_hz = 16000.0;
  std::string length = "1.0";     // seconds, or "auto" (Model::auto_length_s per RIR)
  std::string model = "gas";
  uint64_t seed = 0;
  int num_threads = 1;
  SampleFormat format = SampleFormat::kInt16;
  PolarPattern mic_pattern = PolarPattern::kOmni;     // for lines without mic_pattern=
  PolarPattern source_pattern = PolarPattern::kOmni;  // for lines without src_pattern=

  // --sample-rate (alias --fs), --length, --model, --mic-pattern, --src-pattern, --seed (alias
  // --random-seed), --num-threads, --format.
  void Register(OptionsItf* opts);
};

// `room` with its unset polar patterns taken from the options.
RoomSpec with_default_patterns(const RoomSpec& room, const SimulateOptions& options);

// Length in samples for one room ("auto" or seconds); throws Error for a bad length string.
size_t rir_length_samples(const std::string& length, double auto_length_s, double sample_rate_hz);

// Validates the options and every room before rendering anything, renders in parallel, and writes
// <out_dir>/<rir-id>.wav, rir.scp and rir_list as one unit (nothing is left behind on error).
// A line with a microphone array gives one multichannel WAV, channel c = microphone c.
// Amplitudes are physical (direct sound 1/(4 pi r)): int16 output of a source within ~8 cm of the
// microphone exceeds full scale, which the RIR writer refuses (use float output).
void simulate_room_list(const std::vector<RoomSpec>& rooms, const std::string& out_dir,
                             const SimulateOptions& options);

}  // namespace tsrir::sim
