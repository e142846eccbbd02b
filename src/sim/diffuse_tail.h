// "diffuse": the stochastic late part. Per band, noise whose expected energy density follows the
// diffuse field of the room, c / (4 pi V) exp(-rate t) with Eyring's rate (sum of squared samples
// per second; the same normalisation as the image sources' 1 / (4 pi r) amplitudes).
//  - Before the image-source transition t_tr it carries only the scattered share,
//    1 - (1 - s)^k(t), where k(t) = c t S / 4V is the mean reflection count; the specular images
//    carry the rest, so the sum has the full diffuse energy.
//  - From t_tr on it carries everything.
//  - With "ism" in the model, its level is scaled per band by the ratio of the image energy to
//    the statistical energy in [t_tr/2, t_tr), so the energy is continuous at the transition
//    (ratio clamped to [0.25, 4] against degenerate geometry).
// One white noise sequence (variance 1, uniform) is shared by all bands: the band filters make the
// bands disjoint, and near crossovers the shared noise interpolates the envelopes coherently.
// No parameters.
#pragma once
#include "sim/model.h"

namespace tsrir::sim {

class DiffuseTailComponent : public ModelComponent {
 public:
  explicit DiffuseTailComponent(ComponentParams& params);
  std::string name() const override { return "diffuse"; }
  ModelStage stage() const override { return ModelStage::kBands; }
  int order() const override { return 200; }
  double max_decay_time_s(const RoomSpec& room) const override;
  void render_bands(const RenderContext& ctx, BandSignals& bands) const override;
};

}  // namespace tsrir::sim
