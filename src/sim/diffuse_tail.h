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
// Polar patterns: a microphone picks up, and a source radiates, the share mean(g^2) of a diffuse
// field's energy (sim/polar_pattern.h: 1/3 for a cardioid); the tail is scaled by the square root
// of the product of the two.
// Arrays: each microphone draws its own white noise (its own stream), and the noises are mixed per
// frequency so that the tails of microphones i and j a distance d apart have the spatial coherence
// of an isotropic diffuse field, sin(kd)/(kd) with k = 2 pi f / c (Cook et al. 1955; the mixing is
// Habets & Gannot's 2007 per-bin matrix factorisation). The coherence is that of omnidirectional
// microphones whatever their pattern (an approximation for directional ones).
// No parameters.
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

// Mixes independent white noises (one per microphone, all the same length) into noises with the
// diffuse-field coherence sin(k d_ij)/(k d_ij) between microphones i and j, k = 2 pi f / c: per FFT
// bin, the Cholesky factor of that matrix (its diagonal loaded by 1e-6, so that it exists where the
// microphones are close compared to the wavelength) mixes the noises' spectra. Each output keeps
// its input's variance; noise 0 passes unchanged up to the loading and float rounding.
std::vector<std::vector<float>> diffuse_coherent_noise(const std::vector<std::vector<float>>& white,
                                                       const std::vector<Vec3>& mics_m, double speed_of_sound_m_s,
                                                       double sample_rate_hz);

class DiffuseTailComponent : public ModelComponent {
 public:
  explicit DiffuseTailComponent(ComponentParams& params);
  std::string name() const override { return "diffuse"; }
  ModelStage stage() const override { return ModelStage::kBands; }
  int order() const override { return 200; }
  double max_decay_time_s(const RoomSpec& room) const override;
  void render_bands(const RenderContext& ctx, BandSignals& bands) const override;
  void render_array_bands(const std::vector<const RenderContext*>& ctxs,
                          const std::vector<BandSignals*>& bands) const override;

 private:
  // Adds the tail to `bands`; white[i] is the noise sample at time i (read from the direct delay on).
  void add_tail(const RenderContext& ctx, const float* white, BandSignals& bands) const;
};

}  // namespace tsrir::sim
