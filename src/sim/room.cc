#include "sim/room.h"

#include <cmath>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir::sim {
namespace {

// 6 ln(10): the natural-log decay of 60 dB of energy.
constexpr double kLn60dB = 13.815510557964274;

std::string prefixed(const std::string& where, const std::string& message) {
  return where.empty() ? message : where + ": " + message;
}

}  // namespace

const char* surface_name(int surface) {
  static const char* const kNames[kNumSurfaces] = {"x0", "x1", "y0", "y1", "floor", "ceiling"};
  if (surface < 0 || surface >= kNumSurfaces) throw Error("surface index out of range");
  return kNames[surface];
}

double RoomSpec::volume_m3() const { return size_m[0] * size_m[1] * size_m[2]; }

double RoomSpec::surface_area_m2(int surface) const {
  const int axis = surface / 2;  // the wall's normal axis
  return size_m[(axis + 1) % 3] * size_m[(axis + 2) % 3];
}

double RoomSpec::surface_area_m2() const {
  double total = 0.0;
  for (int s = 0; s < kNumSurfaces; ++s) total += surface_area_m2(s);
  return total;
}

double RoomSpec::source_mic_distance_m() const {
  const double dx = source_m[0] - mic_m[0], dy = source_m[1] - mic_m[1], dz = source_m[2] - mic_m[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

PolarPattern source_pattern_in_band(const RoomSpec& room, int band) {
  if (room.source_band_patterns) return (*room.source_band_patterns)[static_cast<size_t>(band)];
  return room.source_pattern.value_or(PolarPattern::kOmni);
}

bool has_directional_transducers(const RoomSpec& room) {
  if (room.mic_pattern.value_or(PolarPattern::kOmni) != PolarPattern::kOmni) return true;
  for (int b = 0; b < kNumOctaveBands; ++b)
    if (source_pattern_in_band(room, b) != PolarPattern::kOmni) return true;
  return false;
}

BandValues source_pattern_gains(const RoomSpec& room, const Vec3& departure) {
  BandValues gains{};
  for (int b = 0; b < kNumOctaveBands; ++b)
    gains[b] = polar_gain(source_pattern_in_band(room, b), room.source_axis, departure);
  return gains;
}

BandValues source_diffuse_energy(const RoomSpec& room) {
  BandValues energy{};
  for (int b = 0; b < kNumOctaveBands; ++b) energy[b] = polar_diffuse_energy(source_pattern_in_band(room, b));
  return energy;
}

RoomSpec RoomSpec::for_mic(size_t mic) const {
  RoomSpec single = *this;
  single.mic_m = mic_position_m(mic);
  single.array_m.clear();
  return single;
}

double speed_of_sound_from_temperature_m_s(double temperature_c) {
  return 331.3 * std::sqrt(1.0 + temperature_c / 273.15);
}

BandValues mean_absorption(const RoomSpec& room) {
  BandValues mean{};
  const double area = room.surface_area_m2();
  for (int s = 0; s < kNumSurfaces; ++s) {
    const double w = room.surface_area_m2(s) / area;
    for (int b = 0; b < kNumOctaveBands; ++b) mean[b] += w * room.absorption[s][b];
  }
  return mean;
}

BandValues eyring_decay_rate_per_s(const RoomSpec& room) {
  const BandValues a = mean_absorption(room);
  BandValues rate{};
  const double k = room.speed_of_sound_m_s * room.surface_area_m2() / (4.0 * room.volume_m3());
  for (int b = 0; b < kNumOctaveBands; ++b) {
    rate[b] = a[b] >= 1.0 ? INFINITY : -k * std::log1p(-a[b]);
  }
  return rate;
}

BandValues eyring_t60_s(const RoomSpec& room) {
  const BandValues rate = eyring_decay_rate_per_s(room);
  BandValues t60{};
  for (int b = 0; b < kNumOctaveBands; ++b) t60[b] = std::isinf(rate[b]) ? 0.0 : kLn60dB / rate[b];
  return t60;
}

double eyring_absorption_for_t60(double t60_s, double volume_m3, double area_m2,
                                 double speed_of_sound_m_s, const std::string& context) {
  if (!(t60_s > 0.0) || !std::isfinite(t60_s)) {
    throw Error(prefixed(context, "t60 must be positive, got " + format_double(t60_s)));
  }
  // From T60 = 4 ln(10^6) V / (-c S ln(1 - a)).
  const double a = -std::expm1(-4.0 * kLn60dB * volume_m3 / (speed_of_sound_m_s * area_m2 * t60_s));
  if (a < kMinReachableAbsorption) {
    const double t_max = 4.0 * kLn60dB * volume_m3 /
                         (-speed_of_sound_m_s * area_m2 * std::log1p(-kMinReachableAbsorption));
    throw Error(prefixed(context, "t60=" + format_double(t60_s) +
                                      " s cannot be reached in this room: it needs a mean absorption of " +
                                      format_double(a, 3) + " (< " + format_double(kMinReachableAbsorption) +
                                      "); the longest reachable T60 is " + format_double(t_max, 3) + " s"));
  }
  return a;
}

void validate_room(const RoomSpec& room) {
  const std::string& w = room.where;
  for (int i = 0; i < 3; ++i) {
    if (!(room.size_m[i] > 0.0) || !std::isfinite(room.size_m[i])) {
      throw Error(prefixed(w, "room dimensions must be positive and finite, got " +
                                  format_double(room.size_m[0]) + "," + format_double(room.size_m[1]) + "," +
                                  format_double(room.size_m[2])));
    }
  }
  auto check_inside = [&](const Vec3& p, const char* what) {
    for (int i = 0; i < 3; ++i) {
      if (!(p[i] > 0.0 && p[i] < room.size_m[i])) {
        throw Error(prefixed(w, std::string(what) + " position " + format_double(p[0]) + "," +
                                    format_double(p[1]) + "," + format_double(p[2]) +
                                    " is not strictly inside the room " + format_double(room.size_m[0]) +
                                    " x " + format_double(room.size_m[1]) + " x " +
                                    format_double(room.size_m[2]) + " m"));
      }
    }
  };
  check_inside(room.source_m, "source");
  for (size_t m = 0; m < room.num_mics(); ++m) {
    const std::string what = room.array_m.empty() ? "microphone" : "microphone " + std::to_string(m + 1);
    check_inside(room.mic_position_m(m), what.c_str());
    if (room.for_mic(m).source_mic_distance_m() < 1e-3) {
      throw Error(prefixed(w, "source and " + what + " are at the same point"));
    }
  }
  for (int s = 0; s < kNumSurfaces; ++s) {
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const double a = room.absorption[s][b];
      if (!(a > 0.0 && a <= 1.0)) {
        throw Error(prefixed(w, std::string("absorption of surface ") + surface_name(s) + " at " +
                                    octave_band_label(kOctaveCentersHz[b]) + " Hz is " + format_double(a) +
                                    ", outside (0,1]"));
      }
    }
  }
  for (int b = 0; b < kNumOctaveBands; ++b) {
    const double s = room.scattering[b];
    if (!(s >= 0.0 && s <= 1.0)) {
      throw Error(prefixed(w, "scattering at " + octave_band_label(kOctaveCentersHz[b]) + " Hz is " +
                                  format_double(s) + ", outside [0,1]"));
    }
  }
  if (!(room.speed_of_sound_m_s > 100.0 && room.speed_of_sound_m_s < 1000.0)) {
    throw Error(prefixed(w, "speed of sound " + format_double(room.speed_of_sound_m_s) +
                                " m/s is not plausible for air"));
  }
}

}  // namespace tsrir::sim
