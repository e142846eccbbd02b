// Test-side generation of "measured" RIR sets: the baseline simulator renders the stated rooms
// (the truth model the real world departs from), then one or more effects of rir-diagnose's
// catalog are hidden with formulations written here, independently of the extension components
// under test (different maths, different code):
//   room_modes          damped sinusoids at shoebox mode frequencies computed here, amplitudes from
//                       cos mode shapes with random jitter, decays 1.5-2.5x the stated low-band T60
//   air_absorption      ISO 9613-1 (own implementation) applied per STFT bin and frame time
//   band_absorption     rendering with per-band absorption the room list does not state
//   transducer_response a random cascade of RBJ peaking/shelving biquads (direct form)
//   noise_floor         white or pink Gaussian noise (FFT-shaped) at a random peak-to-noise ratio
//   diffuse_scattering  rendering with scattering the room list does not state
//   time_offset         a random latency (integer-sample shift)
#pragma once
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::testing {

struct HiddenSet {
  std::vector<sim::RoomSpec> stated;       // what the room list says
  std::vector<Signal> measured;            // what the "measurement" gives
  std::map<std::string, double> truth;     // hidden parameters, for the parameter checks
};

// `count` set-ups in one mid-size room (6.2 x 4.8 x 3.0 m, stated absorption rising with
// frequency), positions drawn with `seed`.
std::vector<sim::RoomSpec> make_test_rooms(size_t count, uint64_t seed);

// Renders the stated rooms and hides `effects` (ids of the catalog) with parameters drawn from
// `seed`.
HiddenSet make_hidden_set(const std::vector<sim::RoomSpec>& rooms, const std::set<std::string>& effects,
                          uint64_t seed, double sample_rate_hz = 16000.0, double length_s = 1.0);

// ISO 9613-1 attenuation (dB/m), written for the tests.
double test_air_attenuation_db_per_m(double f_hz, double temperature_c, double humidity_percent);

}  // namespace tsrir::testing
