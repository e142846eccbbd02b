#include "io/sox_api.h"

#include "util/dynamic_library.h"

namespace tsrir {

const SoxApi& sox() {
  static const SoxApi api = [] {
    static const DynamicLibrary lib(TSRIR_SOX_SONAME, "to resample audio");
    SoxApi a;
    a.init = lib.function<decltype(a.init)>("sox_init");
    a.get_globals = lib.function<decltype(a.get_globals)>("sox_get_globals");
    a.create_effects_chain = lib.function<decltype(a.create_effects_chain)>("sox_create_effects_chain");
    a.delete_effects_chain = lib.function<decltype(a.delete_effects_chain)>("sox_delete_effects_chain");
    a.create_effect = lib.function<decltype(a.create_effect)>("sox_create_effect");
    a.find_effect = lib.function<decltype(a.find_effect)>("sox_find_effect");
    a.effect_options = lib.function<decltype(a.effect_options)>("sox_effect_options");
    a.add_effect = lib.function<decltype(a.add_effect)>("sox_add_effect");
    a.flow_effects = lib.function<decltype(a.flow_effects)>("sox_flow_effects");
    return a;
  }();
  return api;
}

}  // namespace tsrir
