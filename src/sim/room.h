// A shoebox room set-up as the simulator sees it: geometry, source and microphone, and the
// acoustic properties of its six surfaces per octave band (the 8 bands of dsp/bands.h, 62.5 Hz to
// 8 kHz, as GSound uses). One RoomSpec describes one RIR to simulate.
//
// Coordinates: the room spans [0, Lx] x [0, Ly] x [0, Lz] metres; z is height (floor z = 0).
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "dsp/bands.h"
#include "sim/polar_pattern.h"

namespace tsrir::sim {

// One value per octave band, index i <-> kOctaveCentersHz[i].
using BandValues = std::array<double, kNumOctaveBands>;
using Vec3 = std::array<double, 3>;

// Surfaces in a fixed order: the two x walls, the two y walls, floor, ceiling.
enum Surface : int { kWallX0 = 0, kWallX1 = 1, kWallY0 = 2, kWallY1 = 3, kFloor = 4, kCeiling = 5 };
constexpr int kNumSurfaces = 6;
// "x0", "x1", "y0", "y1", "floor", "ceiling" (the names used by room-list keys).
const char* surface_name(int surface);

constexpr double kDefaultSpeedOfSound_m_s = 343.0;
// Below this mean absorption a t60 target is rejected as unreachable by real surfaces (it would
// also need an absurd number of image sources).
constexpr double kMinReachableAbsorption = 0.01;

struct RoomSpec {
  std::string rir_id;
  std::string room_id;                       // Kaldi --room-id; empty = rir_id
  Vec3 size_m{0.0, 0.0, 0.0};                // Lx, Ly, Lz
  Vec3 source_m{0.0, 0.0, 0.0};
  Vec3 mic_m{0.0, 0.0, 0.0};
  // A microphone array: every microphone's position in array order (= the channel order of the
  // RIR). Empty: one microphone at mic_m. With an array, mic_m is its first microphone.
  std::vector<Vec3> array_m;
  // Polar patterns and unit axes (sim/polar_pattern.h); the microphones of an array share theirs.
  // Unset patterns are omni (rir-simulate fills them from --mic-pattern / --src-pattern).
  std::optional<PolarPattern> mic_pattern, source_pattern;
  // A loudspeaker's pattern per octave band (62.5 Hz .. 8 kHz; room-list src_pattern_bands=): when
  // set it replaces source_pattern band by band (omni at low frequencies, directional above).
  std::optional<std::array<PolarPattern, kNumOctaveBands>> source_band_patterns;
  Vec3 mic_axis{1.0, 0.0, 0.0};
  Vec3 source_axis{1.0, 0.0, 0.0};
  // Random-incidence energy absorption coefficient per surface and band, in (0, 1].
  std::array<BandValues, kNumSurfaces> absorption{};
  // Fraction of the reflected energy scattered diffusely at each reflection, per band, [0, 1].
  BandValues scattering{};
  double temperature_c = 20.0;               // used by air absorption (and c when given)
  double relative_humidity_percent = 50.0;   // used by air absorption
  double speed_of_sound_m_s = kDefaultSpeedOfSound_m_s;
  std::string where;                         // "file:line" of its room-list line, for messages

  const std::string& effective_room_id() const { return room_id.empty() ? rir_id : room_id; }
  double volume_m3() const;
  double surface_area_m2() const;            // all six surfaces
  double surface_area_m2(int surface) const;
  double source_mic_distance_m() const;     // to mic_m
  size_t num_mics() const { return array_m.empty() ? 1 : array_m.size(); }
  Vec3 mic_position_m(size_t mic) const { return array_m.empty() ? mic_m : array_m.at(mic); }
  // The same set-up seen by one microphone of the array alone (mic_m = its position, no array).
  RoomSpec for_mic(size_t mic) const;
};

// The source's pattern in octave band `band`: source_band_patterns when given, else
// source_pattern, else omni.
PolarPattern source_pattern_in_band(const RoomSpec& room, int band);
// Whether any band of the source, or the microphone, has a pattern other than omni.
bool has_directional_transducers(const RoomSpec& room);
// Per band: the source's gain towards unit direction `departure` (polar_gain), and the share
// mean(g^2) of its power it radiates into a diffuse field (polar_diffuse_energy).
BandValues source_pattern_gains(const RoomSpec& room, const Vec3& departure);
BandValues source_diffuse_energy(const RoomSpec& room);

// c = 331.3 * sqrt(1 + T / 273.15) m/s (dry air; 343.2 m/s at 20 C).
double speed_of_sound_from_temperature_m_s(double temperature_c);

// Area-weighted mean absorption per band.
BandValues mean_absorption(const RoomSpec& room);

// Eyring: T60 = 24 ln(10) V / (-c S ln(1 - a_mean)) per band (no air absorption). a_mean = 1
// gives 0.
BandValues eyring_t60_s(const RoomSpec& room);
// Energy decay rate of the diffuse field per band, 1/s: E(t) ~ exp(-rate * t).
BandValues eyring_decay_rate_per_s(const RoomSpec& room);

// The mean absorption that gives `t60_s` by Eyring in a room of this volume, area and c. Throws
// Error (message prefixed by `context`) if t60_s is not positive and finite, or needs a mean
// absorption below kMinReachableAbsorption.
double eyring_absorption_for_t60(double t60_s, double volume_m3, double area_m2,
                                 double speed_of_sound_m_s, const std::string& context);

// Checks everything the simulator relies on; throws Error prefixed by room.where: positive finite
// dimensions, source and microphone strictly inside the room and not at the same point,
// absorption in (0, 1], scattering in [0, 1], positive c; every microphone of an array likewise.
void validate_room(const RoomSpec& room);

}  // namespace tsrir::sim
