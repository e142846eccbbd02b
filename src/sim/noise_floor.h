// "noise_floor": stationary measurement noise added to the RIR, so that its decay flattens at the
// level a real measurement shows. The noise is white shaped by a spectral tilt; its level is
// relative to the RIR's own energy (the measured RIRs' absolute scale is arbitrary):
//   level_db            power per sample of the noise's 1 kHz spectral density expressed as white
//                       noise, relative to the energy (sum of squares) of the noiseless RIR, dB
//                       (default -100);
//   tilt_db_per_octave  spectral slope (0 = white, -3 = pink; default 0), applied between
//   min_hz and max_hz   (defaults 20 Hz and Nyquist): the spectrum is held constant outside, so a
//                       slope fitted on a few bands is not extrapolated to huge levels.
#pragma once
#include "sim/model.h"

namespace tsrir::sim {

// Power gain of the tilt at f_hz (1 at 1 kHz), f clamped to [min_hz, max_hz].
double noise_tilt_power_gain(double f_hz, double tilt_db_per_octave, double min_hz = 20.0, double max_hz = 1e9);

class NoiseFloorComponent : public ModelComponent {
 public:
  explicit NoiseFloorComponent(ComponentParams& params);
  std::string name() const override { return "noise_floor"; }
  ModelStage stage() const override { return ModelStage::kBroadband; }
  int order() const override { return 400; }
  void process_rir(const RenderContext& ctx, std::vector<float>& samples) const override;

 private:
  double level_db_;
  double tilt_db_per_octave_;
  double min_hz_, max_hz_;
};

}  // namespace tsrir::sim
