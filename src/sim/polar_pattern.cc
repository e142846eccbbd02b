#include "sim/polar_pattern.h"

#include <cmath>

namespace tsrir::sim {

const Choices<PolarPattern>& polar_pattern_choices() {
  static const Choices<PolarPattern> choices = {{"omni", PolarPattern::kOmni},
                                                {"subcardioid", PolarPattern::kSubcardioid},
                                                {"cardioid", PolarPattern::kCardioid},
                                                {"hypercardioid", PolarPattern::kHypercardioid},
                                                {"figure8", PolarPattern::kFigure8}};
  return choices;
}

double polar_pattern_alpha(PolarPattern pattern) {
  switch (pattern) {
    case PolarPattern::kOmni: return 1.0;
    case PolarPattern::kSubcardioid: return 0.75;
    case PolarPattern::kCardioid: return 0.5;
    case PolarPattern::kHypercardioid: return 0.25;
    case PolarPattern::kFigure8: return 0.0;
  }
  return 1.0;
}

double polar_gain(PolarPattern pattern, const Vec3& axis_unit, const Vec3& direction_unit) {
  const double alpha = polar_pattern_alpha(pattern);
  if (alpha == 1.0) return 1.0;
  const double cos_theta =
      axis_unit[0] * direction_unit[0] + axis_unit[1] * direction_unit[1] + axis_unit[2] * direction_unit[2];
  return alpha + (1.0 - alpha) * cos_theta;
}

double polar_diffuse_energy(PolarPattern pattern) {
  const double alpha = polar_pattern_alpha(pattern);
  return alpha * alpha + (1.0 - alpha) * (1.0 - alpha) / 3.0;
}

Vec3 axis_from_degrees(double azimuth_deg, double elevation_deg) {
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  const double az = azimuth_deg * kDegToRad, el = elevation_deg * kDegToRad;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

}  // namespace tsrir::sim
