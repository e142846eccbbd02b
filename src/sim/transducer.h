// "transducer": the colouration of a loudspeaker/microphone chain, as a minimum-phase filter whose
// magnitude is given per octave band (dB) and interpolated smoothly in log frequency; it colours
// the direct sound and the tail alike. Parameters: g62.5, g125, ..., g8000 (dB, default 0).
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

// Parameter key of a band's gain: "g62.5", "g125", ...
std::string transducer_gain_key(int band);

// The 1024-tap (at 16 kHz; scaled with the rate) minimum-phase filter for these band gains.
std::vector<float> transducer_filter(const BandValues& gains_db, double sample_rate_hz);

class TransducerComponent : public ModelComponent {
 public:
  explicit TransducerComponent(ComponentParams& params);
  std::string name() const override { return "transducer"; }
  ModelStage stage() const override { return ModelStage::kBroadband; }
  int order() const override { return 200; }
  void process_rir(const RenderContext& ctx, std::vector<float>& samples) const override;

 private:
  BandValues gains_db_{};
};

}  // namespace tsrir::sim
