#include "sim/room_refits.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace tsrir::sim {

std::string band_absorption_key(int band) { return "s" + octave_band_label(kOctaveCentersHz[band]); }

BandAbsorptionComponent::BandAbsorptionComponent(ComponentParams& params) {
  for (int b = 0; b < kNumOctaveBands; ++b) {
    scale_[b] = params.number(band_absorption_key(b), 1.0);
    if (!(scale_[b] > 0.0 && scale_[b] <= 100.0)) {
      throw Error("model component band_absorption: " + band_absorption_key(b) + " must be in (0, 100]");
    }
  }
}

void BandAbsorptionComponent::adjust_room(RoomSpec& room) const {
  for (auto& surface : room.absorption) {
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const double a = std::min(surface[b], 0.999);
      // 1 - a' = (1 - a)^s; capped below 1 so that no band loses its decay entirely.
      surface[b] = std::clamp(-std::expm1(scale_[b] * std::log1p(-a)), 1e-4, 0.999);
    }
  }
}

ScatteringComponent::ScatteringComponent(ComponentParams& params) : value_(params.number("value", 0.1)) {
  if (!(value_ >= 0.0 && value_ <= 1.0)) throw Error("model component scattering: value must be in [0, 1]");
}

void ScatteringComponent::adjust_room(RoomSpec& room) const { room.scattering.fill(value_); }

}  // namespace tsrir::sim
