// An independent "measured RIR" generator for rir-diagnose's tests. It shares no code and no
// formulation with src/sim (the diagnosis' baseline "gas" = ism + diffuse): only the data types
// (RoomSpec, Signal) and the FFT engine are common.
//
//   Early part   image sources of a shoebox enumerated per axis (image k of an axis sits at
//                k L + (k even ? s : L - s) and hits the walls |k| times), summed EXACTLY in the
//                frequency domain (each image is H_i(f) exp(-j 2 pi f tau_i) on a 7.8 Hz grid, no
//                fractional-delay filter, no octave filter bank): the reflection gain of an image
//                is interpolated between octave centres in ln(gain) over log frequency, air
//                attenuation (ISO 9613-1, own code) is applied at every frequency bin over the
//                image's path. Images fade out over a raised-cosine crossfade around
//                kMixingTimeS (gas switches at a transition time set by an image count, with an
//                energy calibration; this one has none).
//   Diffuse part Gaussian noise shaped in an STFT (sqrt-Hann, 512/128 at 16 kHz) by a
//                time-frequency energy envelope: (a) scattered energy "rain": every image's
//                scattered share 1 - (1 - s)^n of its energy is re-emitted as diffuse energy
//                spread after its arrival over one mean free time (exponential kernel), and
//                (b) from the crossfade on, the statistical diffuse field c / (4 pi V)
//                exp(-rate(f) t) with Eyring's rate (own formula) interpolated in log frequency
//                and the air's rate added per bin. No calibration against the image energy.
//   Modal part   (optional) damped sinusoids at the modes of the TRUE room (whose size may differ
//                from the stated one), random phases, cos mode shapes at the true positions.
//   Modal field  (optional) a room's modal field as real rooms have it: EVERY mode of the true room
//                from 20 Hz to somewhat past its Schroeder frequency, each with the amplitude of the
//                modal Green's function (mode shapes at the true positions, no random jitter) and
//                its own damping from the walls it meets (Morse & Bolt: an axial mode meets two
//                walls head-on and grazes the others, so it decays more slowly than an oblique one;
//                the tail's Eyring rate is an oblique mode's), summed in the FREQUENCY domain as
//                Lorentzian transfer functions (not the time-domain sum of the old modal part, nor
//                the simulator's: src/sim/room_modes.h damps every mode at its band's rate).
//   Source       (optional) a directional source aimed at the true microphone: power pattern
//                (m + 1) ((1 + cos theta) / 2)^m with m = Q - 1 (power-normalised: its mean over
//                the sphere is 1, so the diffuse field keeps its level), Q from the on-axis
//                directivity index per octave, interpolated in log frequency per bin. Every image
//                gets the gain of the direction it leaves the real source in (the image's
//                direction to the microphone, mirrored back per axis), its scattered energy too.
//   Outside the catalog of rir-diagnose (what no effect names; tests of what it says then):
//   Non-shoebox  (optional) a convex prism room (a floor polygon, e.g. splayed side walls): its
//                image sources by mirroring across its planes with Borish's path check, the diffuse
//                part with its own volume and surface.
//   Coupled room (optional) a second diffuse field from the mixing time on, fed back through an
//                opening from a coupled volume that decays more slowly: a double-slope decay.
//   Flutter echo (optional) a train of reflections between the two x walls (hard and parallel
//                while the rest absorbs) every 2 Lx / c, 1 kHz and up.
//   Transducers  RBJ biquads (peaking, shelving, Butterworth high-pass) in direct form I.
//   Latency      a fractional delay of the whole response (phase ramp on the early part, and
//                the diffuse envelope shifted).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "io/signal.h"
#include "sim/room.h"
#include "util/rng.h"

namespace tsrir::testdata {

// The physical room a "measurement" was taken in (the room list may state something else).
struct TrueRoom {
  sim::Vec3 size_m{};
  sim::Vec3 source_m{}, mic_m{};
  std::array<sim::BandValues, sim::kNumSurfaces> absorption{};  // random incidence, per surface
  sim::BandValues scattering{};
  double speed_of_sound_m_s = 343.0;
  bool air = false;                 // air absorption (ISO 9613-1) on or off
  double air_temperature_c = 20.0;
  double air_humidity_percent = 50.0;
  double air_scale = 1.0;           // multiplies the ISO attenuation (power sweeps)
  double latency_s = 0.0;           // added to every arrival (a constant system latency)
  // Extra modal energy below the Schroeder frequency (room_modes): level re the image sources'
  // modal level and decay factor re the room's own low-band T60; gain_db < -90 = none.
  double mode_gain_db = -100.0;
  double mode_decay_factor = 1.0;
  double mode_max_hz = 180.0;
  // The modal field (modal_gain_db < -90 = none): level re the modal Green's function, every mode's
  // damping divided by modal_decay_factor (> 1: less damped than the walls make it) and spread
  // log-normally per mode by modal_damping_spread (furniture, wall details; natural-log s.d.),
  // modes up to modal_max_factor x the true room's Schroeder frequency (amplitudes tapered over
  // the top half octave).
  double modal_gain_db = -100.0;
  double modal_decay_factor = 1.0;
  double modal_damping_spread = 0.2;
  double modal_max_factor = 1.5;
  // On-axis directivity index of the source per octave band, dB (all 0: an omni source).
  sim::BandValues directivity_db{};
  // Not a shoebox: a prism of height size_m[2] over this convex floor polygon (x, y, counter-
  // clockwise); empty: the shoebox size_m. Each side wall takes the absorption of the shoebox wall
  // its outward normal is nearest to; the source is omni and there are no modal parts.
  std::vector<std::array<double, 2>> floor_polygon;
  // A coupled volume (coupled_level_db < -90 = none): from the mixing time on, a second diffuse
  // field coupled_level_db below the room's own at the mixing time, decaying coupled_decay_factor
  // times more slowly in every band.
  double coupled_level_db = -100.0;
  double coupled_decay_factor = 3.0;
  // Flutter echo (flutter_level_db < -90 = none): reflections every 2 Lx / c after the direct
  // sound, the first flutter_level_db re the direct sound's level at the microphone, each round
  // trip flutter_trip_loss_db weaker (plus the spreading of the longer path), high-passed at 1 kHz
  // (fourth order).
  double flutter_level_db = -100.0;
  double flutter_trip_loss_db = 1.0;
};

// An image source of a convex room: its distance to the microphone and the surfaces (absorption
// indices) of its reflections.
struct ConvexImage {
  double distance_m = 0.0;
  std::vector<int> surfaces;
};
// The image sources of a floor-polygon room within max_distance_m of the microphone (the source
// itself first).
std::vector<ConvexImage> convex_room_images(const TrueRoom& room, double max_distance_m);

// The stated room as the true one (nothing hidden).
TrueRoom true_room_from(const sim::RoomSpec& stated);

// Renders one RIR of num_samples at sample_rate_hz; `rng` draws the diffuse noise and mode phases.
Signal generate_measured_rir(const TrueRoom& room, double sample_rate_hz, size_t num_samples, Rng& rng);

// Test-side ISO 9613-1 attenuation, dB/m, at 101.325 kPa.
double test_air_attenuation_db_per_m(double f_hz, double temperature_c, double humidity_percent);

// Eyring energy decay rate (1/s) per octave band of a shoebox, written for the tests.
sim::BandValues test_eyring_rate_per_s(const TrueRoom& room);

// Schroeder frequency 2000 sqrt(T60 / V) of the true room, T60 of its 125 Hz band (test-side).
double test_schroeder_hz(const TrueRoom& room);

// The modal field of the true room alone (TrueRoom::modal_*), num_samples long, from the source's
// emission at t = 0 (no latency, no fade-in); `rng` draws the per-mode damping spread.
std::vector<double> test_modal_field(const TrueRoom& room, double sample_rate_hz, size_t num_samples, Rng& rng);

// Biquad filters (RBJ audio-EQ cookbook) applied in place, direct form I.
struct TestBiquad { double b0, b1, b2, a1, a2; };
TestBiquad test_peaking(double f0_hz, double gain_db, double q, double fs);
TestBiquad test_high_shelf(double f0_hz, double gain_db, double fs);
TestBiquad test_high_pass(double f0_hz, double q, double fs);   // q = 1/sqrt(2): Butterworth
void apply_test_biquad(const TestBiquad& f, std::vector<float>& x);
// Power gain (dB) of a cascade averaged over the octave around centre_hz.
double test_cascade_octave_gain_db(const std::vector<TestBiquad>& chain, double centre_hz, double fs);

}  // namespace tsrir::testdata
