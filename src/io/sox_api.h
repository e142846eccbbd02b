// libsox, loaded on first use (util/dynamic_library.h): only the resampler (io/resampler.h) needs
// it, and it pulls in ~10 more libraries (codecs, libmagic, libgomp) that a run without
// resampling should not pay for at start-up.
#pragma once
#include <sox.h>

namespace tsrir {

struct SoxApi {
  decltype(&::sox_init) init;
  decltype(&::sox_get_globals) get_globals;
  decltype(&::sox_create_effects_chain) create_effects_chain;
  decltype(&::sox_delete_effects_chain) delete_effects_chain;
  decltype(&::sox_create_effect) create_effect;
  decltype(&::sox_find_effect) find_effect;
  decltype(&::sox_effect_options) effect_options;
  decltype(&::sox_add_effect) add_effect;
  decltype(&::sox_flow_effects) flow_effects;
};

// Loads libsox the first time (thread-safe); throws Error when it cannot be loaded.
const SoxApi& sox();

}  // namespace tsrir
