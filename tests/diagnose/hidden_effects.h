// Test-side "measured" RIR sets for rir-diagnose: every RIR comes from the independent generator
// (measured_rir_generator.h: frequency-domain image sum, STFT-shaped diffuse noise with a
// scattered-energy rain, its own Eyring and ISO 9613-1), never from src/sim. Nothing hidden, the
// "measured" set still differs from the diagnosis' baseline in every detail of its formulation
// (image cut-off, tail synthesis, level calibration): that is the null case. Effects of the catalog
// are hidden as physical properties of the true room or the measurement chain:
//   room_modes          extra damped modes of the TRUE room (size within +-1.5 % of the stated
//                       one), random phases, decays 1.5-2.5x the room's low-band T60; with
//                       HiddenOptions::dense_modes instead the true room's whole modal field (every
//                       mode to 1.5x its Schroeder frequency, Green's-function amplitudes, Morse
//                       damping per mode; measured_rir_generator.h) in a true room whose every
//                       dimension is within +-5 % of the stated one
//   air_absorption      ISO 9613-1 attenuation at every frequency bin over every image's path and
//                       added to the diffuse field's decay rate per bin
//   band_absorption     the true absorption is the stated one times a factor per band
//   transducer_response a random cascade of RBJ peaking/shelving biquads
//   noise_floor         white or pink Gaussian noise (FFT-shaped) at a random peak-to-noise ratio
//   diffuse_scattering  the true scattering coefficient differs from the stated one
//   time_offset         a constant system latency (fractional delay of every arrival)
//   source_directivity  a directional source aimed at the microphone (the generator's pattern on
//                       every image), directivity index 0 dB at 125 Hz rising to 4-8 dB at 2 kHz
// Confounds (HiddenOptions) change the truth without hiding a catalog effect: a loudspeaker's
// low-frequency roll-off, positions and room size that differ from the stated ones.
#pragma once
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::testdata {

struct HiddenSet {
  std::vector<sim::RoomSpec> stated;       // what the room list says
  std::vector<Signal> measured;            // what the "measurement" gives
  std::map<std::string, double> truth;     // hidden parameters, for the parameter checks
};

struct HiddenOptions {
  double highpass_hz = 0.0;        // > 0: a 2nd-order Butterworth high-pass (loudspeaker roll-off)
  double position_error_m = 0.0;   // true source/mic coordinates = stated + U(-e, e)
  double size_error = 0.0;         // true room size = stated * (1 + e), e signed (one per set)
  // > 0: every RIR is pre-aligned as many published sets are: its direct sound moved to this
  // time (ms), whatever the distance (the onset no longer follows the time of flight).
  double pre_align_ms = 0.0;
  // room_modes as the whole modal field of the true room (see above), not the few extra modes.
  bool dense_modes = false;
  // Outside the catalog (measured_rir_generator.h): a coupled volume (a double-slope decay),
  // flutter echo between the x walls, a room that is not a shoebox (the far y wall 2 x splay_m
  // wider than the near one, side walls splayed) measured as the stated shoebox. Parameters drawn
  // after every other draw unless fixed: "coupled_level_db" (-14..-8), "coupled_decay_factor"
  // (2.5..4), "flutter_level_db" (-12..-6), "flutter_trip_loss_db" (0.5..1.5), "splay_m" (0.6..1.2).
  // > 0: the last silent_tail_s of every "measured" file is digital silence (a response cut short
  // and zero-padded, as published sets often are).
  double silent_tail_s = 0.0;
  bool coupled_room = false;
  bool flutter = false;
  bool non_shoebox = false;
  // Fixed hidden parameters instead of drawn ones (names as in HiddenSet::truth, e.g.
  // "scattering", "peak_to_noise_db", "latency_ms", "mode_gain_db", "absorption_factor_3",
  // "humidity_percent", "temperature_c", "transducer_scale" (multiplies the biquad gains),
  // "directivity_db" (the high-frequency directivity index), "modal_gain_db" and
  // "modal_decay_factor" (the dense modal field's level and damping divisor)), and
  // for the power sweeps: "air_scale" (multiplies the ISO attenuation), "transducer_peak_db" (the
  // chain is one peaking filter at 1 kHz, Q 1.4, of this gain), "noise_re_tail" (white noise whose
  // power per sample is this times the clean RIR's mean power over its last 10 %),
  // "directivity_flat_db" (the same directivity index in every band), "noise_late_decay_db" (white
  // noise at the level that leaves the noisy RIR decaying by this much over its last 30 %).
  std::map<std::string, double> fixed;
};

// `count` set-ups in one mid-size room (6.2 x 4.8 x 3.0 m, stated absorption rising with
// frequency), positions drawn with `seed`.
std::vector<sim::RoomSpec> make_test_rooms(size_t count, uint64_t seed);

// Generates the "measured" RIRs of the stated rooms with `effects` (ids of the catalog) hidden,
// parameters drawn from `seed` unless fixed in `options`.
HiddenSet make_hidden_set(const std::vector<sim::RoomSpec>& rooms, const std::set<std::string>& effects,
                          uint64_t seed, double sample_rate_hz = 16000.0, double length_s = 1.0,
                          const HiddenOptions& options = {});

}  // namespace tsrir::testdata
