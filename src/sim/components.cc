// The built-in model components; one register_builtin() line per component.
#include <memory>

#include "sim/builtin_components.h"
#include "sim/diffuse_tail.h"
#include "sim/extension_components.h"
#include "sim/image_sources.h"

namespace tsrir::sim {

void register_builtin_components() {
  register_builtin("ism", "image sources up to the transition time (params: max_images=2000, transition_ms=0 = auto)",
                   [](ComponentParams& p) { return std::make_unique<ImageSourceComponent>(p); });
  register_builtin("diffuse", "stochastic diffuse tail with Eyring decay, energy-matched to the image sources",
                   [](ComponentParams& p) { return std::make_unique<DiffuseTailComponent>(p); });
  register_builtin_alias("gas", "ism+diffuse");
  // The extensions rir-diagnose fits (modes, air, transducer, noise floor, onset shift, refits).
  register_extension_builtins();
}

}  // namespace tsrir::sim
