#include "sim/extension_components.h"

#include <memory>
#include <mutex>
#include <vector>

#include "sim/air_absorption.h"
#include "sim/builtin_components.h"
#include "sim/model.h"
#include "sim/noise_floor.h"
#include "sim/onset_shift.h"
#include "sim/room_modes.h"
#include "sim/room_refits.h"
#include "sim/source_directivity.h"
#include "sim/transducer.h"

namespace tsrir::sim {

namespace {

struct Extension {
  const char* name;
  const char* description;
  ComponentFactory factory;
};

std::vector<Extension> extensions() {
  return {
      {"modes", "low-frequency room modes crossed over with the geometric part "
                "(params: crossover_hz=0 = Schroeder, decay_scale=1, level_db=0)",
       [](ComponentParams& p) { return std::make_unique<RoomModesComponent>(p); }},
      {"air", "ISO 9613-1 air absorption from the room's temperature/humidity (params: humidity=room's, scale=1)",
       [](ComponentParams& p) { return std::make_unique<AirAbsorptionComponent>(p); }},
      {"band_absorption", "per-band absorption refit (params: s62.5..s8000 = factors on -ln(1-a))",
       [](ComponentParams& p) { return std::make_unique<BandAbsorptionComponent>(p); }},
      {"scattering", "scattering coefficient refit (params: value=0.1, all bands)",
       [](ComponentParams& p) { return std::make_unique<ScatteringComponent>(p); }},
      {"directivity", "directional source aimed at the microphone: direct sound raised by the directivity index "
                      "(params: di62.5..di8000 dB, default 0)",
       [](ComponentParams& p) { return std::make_unique<SourceDirectivityComponent>(p); }},
      {"transducer", "minimum-phase transducer colouration (params: g62.5..g8000 dB)",
       [](ComponentParams& p) { return std::make_unique<TransducerComponent>(p); }},
      {"onset_shift", "measurement timing (params: latency_ms=0, align_ms=0 = off)",
       [](ComponentParams& p) { return std::make_unique<OnsetShiftComponent>(p); }},
      {"noise_floor", "stationary measurement noise (params: level_db=-100 re RIR energy, tilt_db_per_octave=0, "
                      "min_hz=20, max_hz)",
       [](ComponentParams& p) { return std::make_unique<NoiseFloorComponent>(p); }},
  };
}

}  // namespace

void register_extension_components() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const Extension& e : extensions()) register_model_component(e.name, e.description, e.factory);
  });
}

void register_extension_builtins() {
  for (const Extension& e : extensions()) register_builtin(e.name, e.description, e.factory);
}

}  // namespace tsrir::sim
