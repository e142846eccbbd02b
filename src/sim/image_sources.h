// "ism": the specular early part by the image-source method (Allen & Berkley) in a shoebox.
// Each image arrives at distance / c as a band-limited fractional-delay impulse (Hann-windowed
// sinc, 16 taps) with per-band amplitude
//   prod_surfaces sqrt(1 - a)^hits * sqrt(1 - s)^reflections / (4 pi distance),
// the sqrt(1 - s) per reflection being the energy the diffuse tail takes over.
// Images are rendered up to the transition time t_tr, chosen so that about `max_images` images
// arrive before it (the shoebox image count grows as 4 pi (c t)^3 / 3V), or given directly as
// transition_ms. Parameters: max_images (default 2000), transition_ms (default 0 = from max_images).
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

struct ImageArrival {
  double delay_s = 0.0;
  double distance_m = 0.0;
  int reflections = 0;
  BandValues amplitude{};           // specular amplitude per band, scattering loss included
  BandValues unscattered_amplitude{};  // the same without the scattering loss
};

// All images with delay < max_delay_s, in no particular order.
std::vector<ImageArrival> image_arrivals(const RoomSpec& room, double max_delay_s);

// Delay before which about `num_images` images arrive (at least the direct delay + 1 ms).
double image_transition_time_s(const RoomSpec& room, double num_images);

class ImageSourceComponent : public ModelComponent {
 public:
  explicit ImageSourceComponent(ComponentParams& params);
  std::string name() const override { return "ism"; }
  ModelStage stage() const override { return ModelStage::kBands; }
  int order() const override { return 100; }
  double max_decay_time_s(const RoomSpec& room) const override;
  void render_bands(const RenderContext& ctx, BandSignals& bands) const override;

  double transition_time_s(const RoomSpec& room) const;

 private:
  double max_images_;
  double transition_s_;
};

// Adds a band-limited impulse of amplitude gain[b] at fractional sample position `position` to
// every band (taps outside the signal are dropped).
void add_fractional_impulse(double position, const BandValues& gain, BandSignals& bands);

}  // namespace tsrir::sim
