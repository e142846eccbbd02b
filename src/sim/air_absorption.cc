#include "sim/air_absorption.h"

#include <cmath>
#include <vector>

#include "util/error.h"

namespace tsrir::sim {

double air_attenuation_db_per_m(double freq_hz, double temperature_c, double relative_humidity_percent) {
  const double t = temperature_c + 273.15;
  const double t0 = 293.15;   // reference air temperature
  const double t01 = 273.16;  // triple-point isotherm temperature
  const double psat_over_pr = std::pow(10.0, -6.8346 * std::pow(t01 / t, 1.261) + 4.6151);
  const double h = relative_humidity_percent * psat_over_pr;  // molar concentration of water vapour, %
  const double fr_o = 24.0 + 4.04e4 * h * (0.02 + h) / (0.391 + h);
  const double fr_n = std::pow(t / t0, -0.5) * (9.0 + 280.0 * h * std::exp(-4.170 * (std::pow(t / t0, -1.0 / 3.0) - 1.0)));
  const double f2 = freq_hz * freq_hz;
  return 8.686 * f2 *
         (1.84e-11 * std::sqrt(t / t0) +
          std::pow(t / t0, -2.5) * (0.01275 * std::exp(-2239.1 / t) / (fr_o + f2 / fr_o) +
                                    0.1068 * std::exp(-3352.0 / t) / (fr_n + f2 / fr_n)));
}

double air_band_decay_increase_per_s(double center_hz, double temperature_c, double relative_humidity_percent,
                                     double speed_of_sound_m_s, double base_rate_per_s) {
  // Energy decay of the band: mean over frequencies (uniform in f) of exp(-(base + m(f) c) t).
  constexpr int kFreqs = 33;
  std::vector<double> extra(kFreqs);
  const double lo = center_hz / std::sqrt(2.0), hi = center_hz * std::sqrt(2.0);
  for (int k = 0; k < kFreqs; ++k) {
    const double f = lo + (hi - lo) * (k + 0.5) / kFreqs;
    const double m = air_attenuation_db_per_m(f, temperature_c, relative_humidity_percent) / (10.0 * std::log10(std::exp(1.0)));
    extra[k] = m * speed_of_sound_m_s;
  }
  auto edc_db = [&](double t) {
    // Backward integral of exp(-r t) is exp(-r t) / r.
    double e = 0.0;
    for (double x : extra) e += std::exp(-(base_rate_per_s + x) * t) / (base_rate_per_s + x);
    return 10.0 * std::log10(e);
  };
  const double e0 = edc_db(0.0);
  // Times where the EDC crosses -5 and -35 dB, by bisection (the EDC is monotone).
  auto crossing = [&](double level_db) {
    double a = 0.0, b = 1.0;
    while (edc_db(b) - e0 > level_db) b *= 2.0;
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (a + b);
      (edc_db(m) - e0 > level_db ? a : b) = m;
    }
    return 0.5 * (a + b);
  };
  const double t5 = crossing(-5.0), t35 = crossing(-35.0);
  // Least-squares slope of the EDC (dB) over [t5, t35].
  constexpr int kPoints = 64;
  double st = 0, sy = 0, stt = 0, sty = 0;
  for (int k = 0; k < kPoints; ++k) {
    const double t = t5 + (t35 - t5) * k / (kPoints - 1);
    const double y = edc_db(t);
    st += t; sy += y; stt += t * t; sty += t * y;
  }
  const double slope_db_per_s = (kPoints * sty - st * sy) / (kPoints * stt - st * st);
  const double rate = -slope_db_per_s / (10.0 * std::log10(std::exp(1.0)));
  return rate - base_rate_per_s;
}

AirAbsorptionComponent::AirAbsorptionComponent(ComponentParams& params)
    : scale_(params.number("scale", 1.0)), humidity_percent_(params.number("humidity", -1.0)) {
  if (!(scale_ >= 0.0 && scale_ <= 100.0)) throw Error("model component air: scale must be in [0, 100]");
  if (!(humidity_percent_ == -1.0 || (humidity_percent_ > 0.0 && humidity_percent_ <= 100.0))) {
    throw Error("model component air: humidity must be in (0, 100] %");
  }
}

void AirAbsorptionComponent::render_bands(const RenderContext& ctx, BandSignals& bands) const {
  const RoomSpec& room = ctx.room;
  const BandValues base = eyring_decay_rate_per_s(room);
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const double base_rate = std::isfinite(base[b]) ? base[b] : 1e3;
    const double extra_rate =
        scale_ * air_band_decay_increase_per_s(kOctaveCentersHz[b], room.temperature_c,
                                               humidity_percent_ > 0.0 ? humidity_percent_ : room.relative_humidity_percent,
                                               room.speed_of_sound_m_s, base_rate);
    // Amplitude factor exp(-extra_rate t / 2), advanced multiplicatively per sample.
    const double step = std::exp(-0.5 * extra_rate / ctx.sample_rate_hz);
    double g = 1.0;
    for (float& x : bands.band[b]) {
      x = static_cast<float>(x * g);
      g *= step;
    }
  }
}

}  // namespace tsrir::sim
