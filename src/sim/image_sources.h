// "ism": the specular early part by the image-source method (Allen & Berkley) in a shoebox.
// Each image arrives at distance / c as a band-limited fractional-delay impulse (Hann-windowed
// sinc, 16 taps) with per-band amplitude
//   prod_surfaces sqrt(1 - a)^hits * sqrt(1 - s)^reflections / (4 pi distance),
// the sqrt(1 - s) per reflection being the energy the diffuse tail takes over.
// Images are rendered up to the transition time t_tr, chosen so that about `max_images` images
// arrive before it (the shoebox image count grows as 4 pi (c t)^3 / 3V), or given directly as
// transition_ms. Microphone and source polar patterns (sim/polar_pattern.h) scale each image by
// the gains at its arrival and departure directions. Parameters: max_images (default 2000), transition_ms (default 0 = from max_images).
#pragma once
#include <vector>

#include "sim/model.h"

namespace tsrir::sim {

struct ImageArrival {
  double delay_s;
  double distance_m;
  int reflections;
  BandValues amplitude;              // specular amplitude per band, scattering loss included
  BandValues unscattered_amplitude;  // the same without the scattering loss
  ImageArrival() : delay_s(0.0), distance_m(0.0), reflections(0), amplitude{}, unscattered_amplitude{} {}
  // Every field left for its maker to set: image_arrivals() fills thousands in place, and zeroing
  // each first cost it a fifth of its time.
  struct Unset {};
  explicit ImageArrival(Unset) {}
};

// One axis of the image lattice: the image's coordinate, whether it is mirrored, its reflections
// and the per-band reflection factor (sqrt(1-a) products of the two walls of this axis).
struct AxisImage {
  double position = 0.0;
  double offset_sq = 0.0;   // (position - the lattice centre's coordinate)^2
  int mirror = 1;           // +1, or -1 where the image is the source mirrored on this axis
  int reflections = 0;
  BandValues factor{};
};
// Sorted by offset_sq (then reflections), images within reach_m of `centre` on this axis.
std::vector<AxisImage> axis_images(double length, double src, double centre, const BandValues& a_low,
                                   const BandValues& a_high, double reach_m);

// The images of room's source within reach_m of `centre`, per axis. It depends on the source and
// the surfaces only, so one lattice (centred on an array) serves every microphone of an array.
struct ImageLattice {
  std::vector<AxisImage> axes[3];
  Vec3 centre{};
  double reach_m = 0.0;
};
ImageLattice image_lattice(const RoomSpec& room, const Vec3& centre, double reach_m);

// The images of `lattice` arriving at room.mic_m with delay < max_delay_s (the lattice must reach
// max_delay_s * c past the microphone), with room's polar patterns applied to `amplitude` (not to
// unscattered_amplitude). Order: by distance from the lattice centre per axis, as enumerated.
std::vector<ImageArrival> image_arrivals(const ImageLattice& lattice, const RoomSpec& room, double max_delay_s);
// All images with delay < max_delay_s at room.mic_m (a lattice centred on it).
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
  // One lattice for the whole array (centred on it), then each microphone's arrivals.
  void render_array_bands(const std::vector<const RenderContext*>& ctxs,
                          const std::vector<BandSignals*>& bands) const override;

  double transition_time_s(const RoomSpec& room) const;

 private:
  void render_microphone(const RenderContext& ctx, const ImageLattice& lattice, double t_tr,
                         BandSignals& bands) const;
  double max_images_;
  double transition_s_;
};

// Adds a band-limited impulse of amplitude gain[b] at fractional sample position `position` to
// every band (taps outside the signal are dropped).
void add_fractional_impulse(double position, const BandValues& gain, BandSignals& bands);

}  // namespace tsrir::sim
