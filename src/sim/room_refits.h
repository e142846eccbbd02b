// Room-stage refits of the surface properties the room list states:
//   "band_absorption"  per-band absorption refitted (Eyring inversion of measured decays): the
//                      absorption exponent -ln(1 - a) of every surface in band b is multiplied by
//                      s<band> (s62.5, s125, ..., s8000; default 1), which multiplies that band's
//                      Eyring decay rate by the same factor.
//   "scattering"       scattering coefficients refitted: value (all bands, in [0, 1]).
#pragma once
#include "sim/model.h"

namespace tsrir::sim {

std::string band_absorption_key(int band);  // "s62.5", "s125", ...

class BandAbsorptionComponent : public ModelComponent {
 public:
  explicit BandAbsorptionComponent(ComponentParams& params);
  std::string name() const override { return "band_absorption"; }
  ModelStage stage() const override { return ModelStage::kRoom; }
  int order() const override { return 100; }
  void adjust_room(RoomSpec& room) const override;

 private:
  BandValues scale_{};
};

class ScatteringComponent : public ModelComponent {
 public:
  explicit ScatteringComponent(ComponentParams& params);
  std::string name() const override { return "scattering"; }
  ModelStage stage() const override { return ModelStage::kRoom; }
  int order() const override { return 200; }
  void adjust_room(RoomSpec& room) const override;

 private:
  double value_;
};

}  // namespace tsrir::sim
