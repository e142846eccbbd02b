#include "sim/simulate.h"

#include <atomic>
#include <cmath>
#include <string>

#include "io/common_options.h"
#include "io/rir_set.h"
#include "sim/model.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir::sim {

void SimulateOptions::Register(OptionsItf* opts) {
  opts->Register("sample-rate", &sample_rate_hz, "sample rate, Hz");
  opts->RegisterAlias("fs", "sample-rate");
  opts->Register("length", &length, "RIR length in seconds, or 'auto' (direct delay + longest band T60)");
  opts->Register("model", &model, "model components, e.g. gas (= ism+diffuse)");
  opts->RegisterEnum("mic-pattern", &mic_pattern, polar_pattern_choices(),
                     "polar pattern of microphones whose room-list line gives no mic_pattern=");
  opts->RegisterEnum("src-pattern", &source_pattern, polar_pattern_choices(),
                     "polar pattern of sources whose room-list line gives no src_pattern=");
  CommonOptions(opts)
      .seed(&seed, "the stochastic parts")
      .threads(&num_threads, "RIRs are rendered in parallel")
      .audio_format(&format);
}

RoomSpec with_default_patterns(const RoomSpec& room, const SimulateOptions& options) {
  RoomSpec out = room;
  if (!out.mic_pattern) out.mic_pattern = options.mic_pattern;
  if (!out.source_pattern) out.source_pattern = options.source_pattern;
  return out;
}

size_t rir_length_samples(const std::string& length, double auto_length_s, double sample_rate_hz) {
  double seconds = auto_length_s;
  if (length != "auto") {
    seconds = parse_double(length, "--length");
    if (!(seconds > 0.0 && seconds <= 60.0)) {
      throw Error("--length must be 'auto' or seconds in (0, 60], got '" + length + "'");
    }
  }
  return static_cast<size_t>(std::llround(seconds * sample_rate_hz));
}

void simulate_room_list(const std::vector<RoomSpec>& rooms, const std::string& out_dir,
                             const SimulateOptions& options) {
  if (!(options.sample_rate_hz >= 1000.0 && options.sample_rate_hz <= 384000.0)) {
    throw Error("--fs must be in [1000, 384000] Hz, got " + format_double(options.sample_rate_hz));
  }
  if (options.num_threads < 1) throw Error("--num-threads must be at least 1");
  const Model model = Model::parse(options.model);
  // Everything that can fail on input fails here, before any output exists.
  std::vector<RoomSpec> prepared;
  std::vector<size_t> lengths;
  for (const RoomSpec& room : rooms) {
    validate_room(room);
    prepared.push_back(model.prepare_room(room));
    lengths.push_back(rir_length_samples(options.length, model.auto_length_s(prepared.back()),
                                         options.sample_rate_hz));
    if (lengths.back() < 16) throw Error(room.where + ": RIR length below 16 samples");
  }

  RirSetWriter writer(out_dir, options.format);
  std::atomic<size_t> done{0};
  const size_t progress_every = std::max<size_t>(1, rooms.size() / 10);
  parallel_for(rooms.size(), options.num_threads, [&](size_t i) {
    const std::vector<Signal> rir = model.render_array(with_default_patterns(rooms[i], options),
                                                        options.sample_rate_hz, lengths[i], options.seed);
    writer.add_channels(rir, rooms[i].effective_room_id());
    const size_t d = ++done;
    if (rooms.size() >= 100 && d % progress_every == 0) {
      log_info("simulated " + std::to_string(d) + " / " + std::to_string(rooms.size()) + " RIRs");
    }
  });
  writer.commit();
}

}  // namespace tsrir::sim
