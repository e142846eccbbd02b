// The built-in catalog of rir-diagnose, in catalog order (findings.json, the summary and the report
// follow it); one line per effect. An effect comes after the effects it depends on (effect.h).
#include <memory>

#include "diagnose/effect.h"

namespace tsrir::diagnose {

std::unique_ptr<Effect> make_room_modes_effect();
std::unique_ptr<Effect> make_air_absorption_effect();
std::unique_ptr<Effect> make_band_absorption_effect();
std::unique_ptr<Effect> make_source_directivity_effect();
std::unique_ptr<Effect> make_transducer_response_effect();
std::unique_ptr<Effect> make_noise_floor_effect();
std::unique_ptr<Effect> make_diffuse_scattering_effect();
std::unique_ptr<Effect> make_time_offset_effect();

const EffectRegistry& effect_registry() {
  static const EffectRegistry registry = [] {
    EffectRegistry r;
    r.add(make_room_modes_effect());
    r.add(make_air_absorption_effect());       // depends on room_modes
    r.add(make_band_absorption_effect());      // depends on room_modes, air_absorption
    r.add(make_source_directivity_effect());   // depends on air_absorption, band_absorption
    r.add(make_transducer_response_effect());  // depends on air/band_absorption, source_directivity
    r.add(make_noise_floor_effect());
    r.add(make_diffuse_scattering_effect());   // depends on source_directivity
    r.add(make_time_offset_effect());
    return r;
  }();
  return registry;
}

}  // namespace tsrir::diagnose
