// "modes": wave behaviour below the Schroeder frequency. The geometric model has no modes: its
// low-frequency response is that of image sources cut at the transition time plus noise. This
// component synthesises the shoebox's low-frequency modes from the modal expansion of the same
// Green's function the image sources use (rigid-wall mode shapes, so amplitudes match the
// 1 / (4 pi r) convention):
//   h(t) = c^2 / V * sum_m psi_m(src) psi_m(mic) / Lambda_m * sin(w_m t) / w_m * exp(-d_m t)
// with psi = cos(nx pi x / Lx) cos(ny pi y / Ly) cos(nz pi z / Lz), Lambda = prod(1 or 1/2), and
// damping d_m from the room's band decay rate at f_m (divided by decay_scale). The modal part
// replaces the geometric part below crossover_hz through complementary one-octave crossovers.
// Parameters: crossover_hz (default 0 = Schroeder frequency 2000 sqrt(T60(125 Hz) / V)),
// decay_scale (default 1: > 1 = longer modal decays), level_db (default 0).
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

struct RoomMode {
  int nx = 0, ny = 0, nz = 0;
  double freq_hz = 0.0;
};

// Rigid-wall shoebox modes with min_hz <= f <= max_hz, ascending in frequency.
std::vector<RoomMode> shoebox_modes(const Vec3& size_m, double speed_of_sound_m_s, double min_hz, double max_hz);

// Schroeder frequency 2000 sqrt(T60 / V) with the Eyring T60 of the 125 Hz band.
double schroeder_frequency_hz(const RoomSpec& room);

// Low-pass gain of the crossover at f_hz (1 below crossover/sqrt2, 0 above crossover*sqrt2).
double modal_crossover_lowpass(double f_hz, double crossover_hz);

class RoomModesComponent : public ModelComponent {
 public:
  explicit RoomModesComponent(ComponentParams& params);
  std::string name() const override { return "modes"; }
  ModelStage stage() const override { return ModelStage::kBroadband; }
  int order() const override { return 100; }
  void process_rir(const RenderContext& ctx, std::vector<float>& samples) const override;

  // The modal part alone (before the crossover), num_samples long.
  std::vector<double> modal_response(const RoomSpec& room, double sample_rate_hz, size_t num_samples,
                                     double direct_delay_s) const;
  double crossover_hz(const RoomSpec& room) const;

 private:
  double crossover_hz_;
  double decay_scale_;
  double level_db_;
};

}  // namespace tsrir::sim
