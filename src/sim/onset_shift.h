// "onset_shift": a measurement system's timing applied to the rendered RIR. Two physical causes
// are distinguished because they look different across positions:
//   latency_ms  a constant delay (sound card / loudspeaker latency): onset = r / c + latency;
//   align_ms    pre-alignment of the files (time of flight removed): the direct sound is moved to
//               align_ms whatever the distance (0 = not aligned).
// The shift is fractional (linear phase in the frequency domain); samples shifted past the end
// are dropped, and an advance drops the start.
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

// Delays x by `shift_samples` (may be negative or fractional), keeping its length.
std::vector<float> fractional_shift(const std::vector<float>& x, double shift_samples);

class OnsetShiftComponent : public ModelComponent {
 public:
  explicit OnsetShiftComponent(ComponentParams& params);
  std::string name() const override { return "onset_shift"; }
  ModelStage stage() const override { return ModelStage::kBroadband; }
  int order() const override { return 300; }
  double max_decay_time_s(const RoomSpec& room) const override;
  void process_rir(const RenderContext& ctx, std::vector<float>& samples) const override;

 private:
  double latency_s_;
  double align_s_;
};

}  // namespace tsrir::sim
