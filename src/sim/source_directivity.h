// "directivity": a directional source aimed at the microphone (a measurement loudspeaker rather than
// an omni source). The image sources of "ism" radiate omnidirectionally; a source of the same sound
// power with directivity factor Q(f) on its axis puts Q times the power into the direct sound while
// the diffuse field, which depends only on the radiated power, stays as it is. This component
// multiplies the direct sound's amplitude by sqrt(Q) per band, i.e. raises the direct-to-
// reverberant ratio by the directivity index DI = 10 log10 Q. Early reflections keep the omni
// amplitudes (they leave the source in other directions, with a gain of 1 on average over the
// sphere). It works in the band stage right after "ism" (order 150), adding (sqrt(Q) - 1) times
// the direct arrival that ism rendered, and does nothing when ism rendered none.
// With a source polar pattern (src_pattern=, src_dir=; sim/polar_pattern.h) the index is the
// source's on-axis directivity index in total (a loudspeaker's data-sheet DI) and the pattern its
// shape: "ism" already gives the direct sound the pattern's gain g(theta) for the direction it
// leaves in (and the microphone pattern's), and the diffuse part is already lowered by mean(g^2) =
// 1 / Q_p, so this component multiplies the direct sound as ism rendered it by
// sqrt(Q / Q_p) = 10^((DI - DI_p) / 20), DI_p = 10 log10 Q_p (4.8 dB for a cardioid): on the axis
// the direct-to-reverberant ratio is raised by DI, as without a pattern; off the axis it follows
// the pattern; the pattern's own index is not counted twice. Without a pattern (omni, Q_p = 1) the
// source is taken to be aimed at the microphone, as before. Why not the alternatives: ignoring the
// pattern (the old behaviour) doubles the index on the axis and raises an off-axis or rear (figure-8:
// inverted) direct sound as if it were on the axis; refusing the combination would leave a
// loudspeaker's measured per-band index without a direction.
// Parameters: di62.5, di125, ..., di8000 (directivity index, dB, default 0; within +-20 dB).
#pragma once
#include <string>

#include "sim/model.h"

namespace tsrir::sim {

// Parameter key of a band's directivity index: "di62.5", "di125", ...
std::string directivity_key(int band);
// The factor this component gives the direct sound that "ism" rendered for `room`, for an index of
// `di_db` in octave band `band`: 10^(di_db / 20) / sqrt(Q_p) with Q_p the directivity factor of the
// source's pattern in that band (source_pattern_in_band).
double directivity_direct_gain(double di_db, const RoomSpec& room, int band);

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
