// "air": frequency-dependent attenuation of sound in air (ISO 9613-1), applied to the octave-band
// signals as an energy decay exp(-m c t) on top of the surfaces' decay (t = time since emission,
// so the direct sound at distance r is attenuated by exp(-m r) and every later arrival by its
// path length). Temperature and humidity come from the room list.
// Parameters: humidity (%, default: the room list's) and scale (default 1, multiplies the
// attenuation): both are fitted by rir-diagnose, since the real humidity is rarely known.
#pragma once
#include "sim/model.h"

namespace tsrir::sim {

// ISO 9613-1 pure-tone attenuation coefficient, dB per metre, at 101.325 kPa.
double air_attenuation_db_per_m(double freq_hz, double temperature_c, double relative_humidity_percent);

// The extra energy decay rate (1/s) that air adds to an octave band whose surface decay rate is
// `base_rate_per_s`: within an octave the attenuation varies ~4x, so the band's decay is not one
// exponential. This is the slope of the band's energy decay (white spectrum inside the band)
// fitted between -5 and -35 dB, minus the base rate. It is what a T30 measurement sees.
double air_band_decay_increase_per_s(double center_hz, double temperature_c, double relative_humidity_percent,
                                     double speed_of_sound_m_s, double base_rate_per_s);

class AirAbsorptionComponent : public ModelComponent {
 public:
  explicit AirAbsorptionComponent(ComponentParams& params);
  std::string name() const override { return "air"; }
  ModelStage stage() const override { return ModelStage::kBands; }
  int order() const override { return 300; }
  void render_bands(const RenderContext& ctx, BandSignals& bands) const override;

 private:
  double scale_;
  double humidity_percent_;  // < 0: the room's
};

}  // namespace tsrir::sim
