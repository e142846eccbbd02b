// What the effects' extension fits share (effect.h: Effect::fit): rendering a set-up with a model
// spec, and how a fitted value is written into a spec.
#pragma once
#include <cstdint>
#include <string>

#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::diagnose {

// Renders one set-up with a model spec at the measured length and rate (the extension components
// registered first).
Signal render_rir(const std::string& model_spec, const sim::RoomSpec& room, double sample_rate_hz, size_t num_samples,
                  uint64_t seed);

// A fitted value in a model spec: 5 significant digits.
std::string spec_num(double v);

}  // namespace tsrir::diagnose
