// First-order polar patterns of microphones and sources: the gain for sound arriving from (or
// leaving towards) a direction at angle theta from the transducer's axis is
//   g(theta) = alpha + (1 - alpha) cos(theta),
// with alpha = 1 (omni), 0.75 (subcardioid), 0.5 (cardioid), 0.25 (hypercardioid), 0 (figure-8),
// the values RIR-Generator (Habets) uses for its 'o', 's', 'c', 'h', 'b' patterns. A figure-8's rear
// lobe has negative gain (polarity inverted), as a real pressure-gradient microphone's.
// Axes are given as azimuth (degrees from +x towards +y) and elevation (degrees above the xy plane).
#pragma once
#include <array>

#include "util/options.h"

namespace tsrir::sim {

using Vec3 = std::array<double, 3>;  // as in sim/room.h (which includes this header)

enum class PolarPattern { kOmni, kSubcardioid, kCardioid, kHypercardioid, kFigure8 };
// "omni", "subcardioid", "cardioid", "hypercardioid", "figure8".
const Choices<PolarPattern>& polar_pattern_choices();

// alpha of g(theta) above.
double polar_pattern_alpha(PolarPattern pattern);
// g for a unit axis and a unit direction (cos theta = their dot product).
double polar_gain(PolarPattern pattern, const Vec3& axis_unit, const Vec3& direction_unit);
// Mean of g^2 over the sphere, alpha^2 + (1 - alpha)^2 / 3: the share of a diffuse field's energy
// the pattern picks up (or, for a source of the same on-axis level, the share of power it radiates).
double polar_diffuse_energy(PolarPattern pattern);

// Unit vector of an azimuth/elevation in degrees.
Vec3 axis_from_degrees(double azimuth_deg, double elevation_deg);

}  // namespace tsrir::sim
