// "directivity": a directional source aimed at the microphone (a measurement loudspeaker rather than
// an omni source). The image sources of "ism" radiate omnidirectionally; a source of the same sound
// power with directivity factor Q(f) on its axis puts Q times the power into the direct sound while
// the diffuse field, which depends only on the radiated power, stays as it is. This component
// multiplies the direct sound's amplitude by sqrt(Q) per band, i.e. raises the direct-to-
// reverberant ratio by the directivity index DI = 10 log10 Q. Early reflections keep the omni
// amplitudes (they leave the source in other directions, with a gain of 1 on average over the
// sphere). It works in the band stage right after "ism" (order 150), adding (sqrt(Q) - 1) times
// the direct arrival that ism rendered, and does nothing when ism rendered none.
// Parameters: di62.5, di125, ..., di8000 (directivity index, dB, default 0; within +-20 dB).
#pragma once
#include <string>

#include "sim/model.h"

namespace tsrir::sim {

// Parameter key of a band's directivity index: "di62.5", "di125", ...
std::string directivity_key(int band);

class SourceDirectivityComponent : public ModelComponent {
 public:
  explicit SourceDirectivityComponent(ComponentParams& params);
  std::string name() const override { return "directivity"; }
  ModelStage stage() const override { return ModelStage::kBands; }
  int order() const override { return 150; }
  void render_bands(const RenderContext& ctx, BandSignals& bands) const override;

 private:
  BandValues di_db_{};
};

}  // namespace tsrir::sim
