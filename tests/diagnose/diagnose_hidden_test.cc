// Hide an effect, require finding it — on "measured" sets from the independent generator
// (measured_rir_generator.h; no src/sim code or formulation). For each case of the catalog (and
// some pairs) rir-diagnose must detect exactly the hidden effects, decided on the fit half only;
// its extended model must reduce the held-out error of the metric the effect acts on (paired
// t-test on the held-out half, p < 0.01); and the fitted parameters must recover the hidden ones
// within the tolerances stated at each check. Null and confound cases (nothing of the catalog
// hidden, or a look-alike) must report nothing spurious.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <set>
#include <string>

#include "diagnose/diagnose.h"
#include "hidden_effects.h"
#include "measured_rir_generator.h"
#include "sim/room_refits.h"

namespace tsrir {
namespace {

constexpr size_t kRirsPerSet = 48;  // 24 fit (decisions, fits) + 24 held out (gains)

// The held-out metric each extension must improve (declared by the effect).
std::string metric_for(const std::string& effect) {
  return diagnose::gain_metric(diagnose::effect_registry().find(effect)->gain_metric()).name;
}

struct Case {
  Case(std::string n, std::set<std::string> h, uint64_t s, testdata::HiddenOptions o = testdata::HiddenOptions(),
       std::set<std::string> u = std::set<std::string>(), std::set<std::string> a = std::set<std::string>())
      : name(std::move(n)), hidden(std::move(h)), seed(s), options(std::move(o)), unasserted(std::move(u)),
        also_expected(std::move(a)) {}
  std::string name;
  std::set<std::string> hidden;
  uint64_t seed;
  testdata::HiddenOptions options;
  // Effects whose detection is not asserted either way (reported): the transducer's
  // low-frequency roll-off, which the short direct-sound window cannot resolve.
  std::set<std::string> unasserted;
  // Effects expected although not hidden through the generator (pre-alignment reads as a time
  // offset, with the alignment as its parameter).
  std::set<std::string> also_expected;
};
// ctest lists a case by its name rather than the struct's bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class HiddenEffectTest : public ::testing::TestWithParam<Case> {};

// TSRIR_DIAGNOSE_SEED_OFFSET=k redraws every case's positions and hidden parameters (for
// checking the decisions' robustness over many draws; the committed suite uses k = 0).
uint64_t seed_offset() {
  const char* s = std::getenv("TSRIR_DIAGNOSE_SEED_OFFSET");
  return s ? std::strtoull(s, nullptr, 10) : 0;
}

double parameter(const diagnose::Finding& f, const std::string& name) {
  for (const auto& [k, v] : f.parameters) {
    if (k == name) return v;
  }
  return NAN;
}

// Recovery of the hidden parameters by the detected effect's fit.
void check_recovery(const diagnose::Finding& f, const testdata::HiddenSet& set, const Case& c) {
  const auto& truth = set.truth;
  if (f.effect == "time_offset" && truth.count("latency_ms")) {
    // Onsets are located to a fraction of a sample; 0.15 ms = 2.4 samples at 16 kHz.
    EXPECT_NEAR(parameter(f, "latency_ms"), truth.at("latency_ms"), 0.15) << c.name;
    EXPECT_NEAR(parameter(f, "onset_vs_flight_slope"), 1.0, 0.05) << c.name;
  }
  if (f.effect == "time_offset" && c.options.pre_align_ms > 0.0) {
    // Pre-aligned: the onset no longer follows the flight time (slope ~0), and the alignment
    // time is found to the same 0.15 ms.
    EXPECT_NEAR(parameter(f, "align_ms"), c.options.pre_align_ms, 0.15) << c.name;
    EXPECT_NEAR(parameter(f, "onset_vs_flight_slope"), 0.0, 0.1) << c.name;
  }
  if (f.effect == "air_absorption" && truth.count("humidity_percent")) {
    // Humidity and temperature trade off (the fit holds the stated 20 C); what decays the tail
    // is the attenuation. The fitted attenuation at 2 and 4 kHz must be within 35 % of the
    // truth's: the top-band decay-rate change it rests on is ~10-30 % and measured to a few
    // per cent per band, i.e. to about a third of the effect.
    const double t_stated = set.stated.front().temperature_c;
    for (double f_hz : {2000.0, 4000.0}) {
      const double fitted = parameter(f, "scale") *
                            testdata::test_air_attenuation_db_per_m(f_hz, t_stated, parameter(f, "humidity_percent"));
      const double real =
          testdata::test_air_attenuation_db_per_m(f_hz, truth.at("temperature_c"), truth.at("humidity_percent"));
      EXPECT_NEAR(fitted / real, 1.0, 0.35) << c.name << " at " << f_hz << " Hz: fitted " << fitted << " dB/m, true " << real;
    }
  }
  // With a directional source hidden as well, the band refit is not checked: its analysis by
  // synthesis steps on the early decay time too, which the raised direct sound shortens in the
  // measurement and not in the (omni) synthesis, so fast bands come out too absorptive (a known
  // limit, reported in bench/RESULTS.md).
  if (f.effect == "band_absorption" && truth.count("absorption_factor_3") && !truth.count("directivity_db_3")) {
    // The decay-rate factor per band, 500 Hz-4 kHz (below twice the Schroeder frequency, ~370
    // Hz here, a band's decay is that of a few modes; the 8 kHz band is cut by Nyquist): within
    // 30 %. The refit's s<band> multiplies the absorption exponent -ln(1 - a), i.e. the Eyring
    // decay rate; the generator multiplies a itself, so the truth compared is the decay-rate
    // change that makes by the generator's own Eyring formula (for a hidden factor of 1.7 on
    // a = 0.35, 2.1; comparing with 1.7 failed draws 4 and 5 of ten by 31-32 % although the
    // refit had found the decay). The hidden factors are 1.35-1.8 or their inverse, so 30 %
    // separates every draw from 1 and from its own inverse; the generator's decay (its own image
    // sum and Eyring tail) differs from the simulator's by a few per cent.
    for (int b = 3; b <= 6; ++b) {
      const double fitted = parameter(f, sim::band_absorption_key(b));
      const double real = truth.at("decay_rate_factor_" + std::to_string(b));
      EXPECT_LT(std::abs(std::log(fitted / real)), std::log(1.3)) << c.name << " band " << b << ": fitted " << fitted
                                                                   << ", true " << real;
    }
  }
  if (f.effect == "transducer_response" && truth.count("transducer_db_3")) {
    // Octave gains 250 Hz-4 kHz within 1 dB (the detector's own effect-size threshold).
    for (int b = 2; b <= 6; ++b) {
      const std::string key = "g" + octave_band_label(kOctaveCentersHz[b]) + "_db";
      EXPECT_NEAR(parameter(f, key), truth.at("transducer_db_" + std::to_string(b)), 1.0) << c.name << " " << key;
    }
  }
  if (f.effect == "noise_floor" && truth.count("noise_level_db")) {
    // Noise level (1 kHz density re the RIR energy) within 3 dB: a factor of 2 in power, the
    // spread of the per-RIR levels the median is taken over.
    EXPECT_NEAR(parameter(f, "level_db"), truth.at("noise_level_db"), 3.0) << c.name;
    // Tilt: white (0) or pink (-3 dB/octave) within 1.5 dB/octave.
    EXPECT_NEAR(parameter(f, "tilt_db_per_octave"), truth.at("pink") > 0.5 ? -3.0 : 0.0, 1.5) << c.name;
  }
  if (f.effect == "source_directivity" && truth.count("directivity_db_3")) {
    // The directivity index 500 Hz-4 kHz within 1 dB, the detector's threshold, when nothing else
    // moves the tail's level. With a band absorption error hidden as well, the tail's reference is
    // the band-refitted simulation, whose decay band_absorption's own check accepts within 30 %;
    // 30 % on the decay rate moves the energy of the 20-300 ms window by up to 4 dB in this room's
    // fastest band (4 kHz at 1.8x absorption: 72 -> 94 per s), so there each band is held to 4 dB.
    const double tolerance_db = truth.count("absorption_factor_3") ? 4.0 : 1.0;
    for (int b = 3; b <= 6; ++b) {
      const std::string key = "di" + octave_band_label(kOctaveCentersHz[b]) + "_db";
      EXPECT_NEAR(parameter(f, key), truth.at("directivity_db_" + std::to_string(b)), tolerance_db) << c.name << " " << key;
    }
  }
  if (f.effect == "diffuse_scattering" && truth.count("scattering")) {
    // Not the same quantity in the two models: the simulator moves a reflection's scattered share
    // into its diffuse tail, the generator spreads it over one mean free time after the
    // reflection ("rain"), so the simulator's early response gets denser per unit of scattering
    // and its matching value is lower than the generator's (0.26-0.30 for a true 0.67-0.95,
    // bench/diagnose/diagnose_probe). What is asserted is the direction and a clear move: more
    // than 0.1 above the stated value (the hidden truth is 0.7-0.85 above it), and not above the
    // truth; the held-out echo-density gain above checks that the value matches the response.
    const double stated = set.stated.front().scattering[3];
    EXPECT_GT(parameter(f, "scattering"), stated + 0.1) << c.name;
    EXPECT_LE(parameter(f, "scattering"), truth.at("scattering") + 0.05) << c.name;
  }
  if (f.effect == "room_modes" && truth.count("mode_decay_factor") && !truth.count("noise_level_db")) {
    // Modal decay relative to the stated low-band decay within 35 %: the low bands' T30 it
    // rests on mixes the modes with the room's own faster decay, so it reads low when the modes
    // are weak (the hidden factor is 1.5-2.5, so 35 % still separates it from 1).
    EXPECT_NEAR(parameter(f, "decay_scale") / truth.at("mode_decay_factor"), 1.0, 0.35) << c.name;
  }
}

TEST_P(HiddenEffectTest, DetectsExactlyTheHiddenEffectsAndTheExtensionHelps) {
  const Case& c = GetParam();
  const uint64_t seed = c.seed + 100 * seed_offset();
  const std::vector<sim::RoomSpec> rooms = testdata::make_test_rooms(kRirsPerSet, 77 + seed);
  const testdata::HiddenSet set = testdata::make_hidden_set(rooms, c.hidden, seed, 16000.0, 1.0, c.options);
  diagnose::DiagnoseOptions options;
  options.num_threads = 2;
  const diagnose::Diagnosis d = diagnose::diagnose_set(set.stated, set.measured, options);
  std::cout << diagnose::diagnosis_summary(d);
  for (const auto& [k, v] : set.truth) std::cout << "  truth " << k << " = " << v << "\n";
  std::set<std::string> expected = c.hidden;
  expected.insert(c.also_expected.begin(), c.also_expected.end());
  std::set<std::string> detected;
  for (const auto& f : d.findings) {
    if (f.detected) detected.insert(f.effect);
    EXPECT_GE(f.confidence, 0.0);
    EXPECT_LE(f.confidence, 1.0);
    if (c.unasserted.count(f.effect)) continue;
    if (f.detected != (expected.count(f.effect) > 0)) std::cout << "  evidence " << f.effect << ": " << f.evidence << "\n";
    EXPECT_EQ(f.detected, expected.count(f.effect) > 0) << c.name << ": " << f.effect << ": " << f.evidence;
  }
  // Every case here is inside the catalog: nothing is left unexplained by the extended model.
  EXPECT_FALSE(d.unexplained.detected) << c.name << ": " << d.unexplained.evidence;
  // Metrics are evaluated where the measurement is above digital silence: the tail level's error
  // is a level difference of responses, never that of a zero-padded end (190 dB before).
  for (const auto& g : d.gains) {
    if (g.name == "tail_level") {
      EXPECT_LT(g.baseline, 80.0) << c.name;
    }
  }
  for (const std::string& effect : expected) {
    if (!detected.count(effect) || c.unasserted.count(effect)) continue;
    const std::string metric = metric_for(effect);
    bool found = false;
    for (const auto& g : d.gains) {
      if (g.name != metric) continue;
      found = true;
      // The extension must reduce the held-out error, significantly by a paired test.
      EXPECT_GT(g.gain, 0.0) << c.name << ": " << metric;
      EXPECT_LT(g.p, diagnose::kGainAlpha) << c.name << ": " << metric << " baseline " << g.baseline << " extended "
                                           << g.extended << " t " << g.t;
    }
    EXPECT_TRUE(found) << metric;
  }
  for (const auto& f : d.findings) {
    if (f.detected) check_recovery(f, set, c);
  }
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

testdata::HiddenOptions rolloff(double hz) {
  testdata::HiddenOptions o;
  o.highpass_hz = hz;
  return o;
}
testdata::HiddenOptions position_error(double m) {
  testdata::HiddenOptions o;
  o.position_error_m = m;
  return o;
}
testdata::HiddenOptions size_error(double e) {
  testdata::HiddenOptions o;
  o.size_error = e;
  return o;
}
testdata::HiddenOptions dense_modes(double decay_factor = 0.0) {
  testdata::HiddenOptions o;
  o.dense_modes = true;
  if (decay_factor > 0.0) o.fixed["modal_decay_factor"] = decay_factor;
  return o;
}
testdata::HiddenOptions dense_modes_low_absorption(double factor) {
  testdata::HiddenOptions o = dense_modes();
  for (int b = 0; b < kNumOctaveBands; ++b) o.fixed["absorption_factor_" + std::to_string(b)] = b <= 2 ? factor : 1.0;
  return o;
}
testdata::HiddenOptions silent_tail(double seconds) {
  testdata::HiddenOptions o;
  o.silent_tail_s = seconds;
  return o;
}
testdata::HiddenOptions pre_aligned(double ms) {
  testdata::HiddenOptions o;
  o.pre_align_ms = ms;
  return o;
}
// A long decay: every band's absorption 0.6x the stated (T60 ~1.6x): the tail is still decaying
// at the end of the file, which must not read as a noise floor.
testdata::HiddenOptions long_decay() {
  testdata::HiddenOptions o;
  for (int b = 0; b < kNumOctaveBands; ++b) o.fixed["absorption_factor_" + std::to_string(b)] = 0.6;
  return o;
}

INSTANTIATE_TEST_SUITE_P(
    Catalog, HiddenEffectTest,
    ::testing::Values(Case{"null_a", {}, 1}, Case{"null_b", {}, 2}, Case{"room_modes", {"room_modes"}, 3},
                      Case{"air_absorption", {"air_absorption"}, 4}, Case{"band_absorption", {"band_absorption"}, 5},
                      Case{"transducer_response", {"transducer_response"}, 6}, Case{"noise_floor", {"noise_floor"}, 7},
                      Case{"diffuse_scattering", {"diffuse_scattering"}, 8},
                      Case{"time_offset", {"time_offset"}, 9},
                      Case{"modes_and_noise", {"room_modes", "noise_floor"}, 10},
                      Case{"transducer_and_offset", {"transducer_response", "time_offset"}, 11},
                      Case{"air_and_scattering", {"air_absorption", "diffuse_scattering"}, 12},
                      Case{"source_directivity", {"source_directivity"}, 13},
                      Case{"directivity_and_band_absorption", {"source_directivity", "band_absorption"}, 14},
                      Case{"directivity_and_transducer", {"source_directivity", "transducer_response"}, 15},
                      // Modal fields as real rooms have them (every mode past the Schroeder
                      // frequency, Morse damping, the true room within +-5 %): at a drawn level and
                      // damping, and with the modes decaying 2.5x more slowly than their walls make
                      // them (the low bands' decay slows too: room_modes, not band_absorption).
                      Case{"dense_modes", {"room_modes"}, 16, dense_modes()},
                      Case{"dense_modes_slow_decay", {"room_modes"}, 17, dense_modes(2.5)},
                      // The low bands (62.5-250 Hz, below twice the Schroeder frequency) absorbing
                      // twice as much under a dense modal field: faster than the modes explain.
                      Case{"dense_modes_and_low_band_absorption", {"room_modes", "band_absorption"}, 18,
                           dense_modes_low_absorption(2.0)}),
    case_name);

// Look-alikes: nothing of the catalog hidden (or one effect whose look-alike must not be
// reported). Air vs per-band absorption is the pair of Catalog cases air_absorption and
// band_absorption (each must report only itself); source directivity vs a decay mismatch
// (band_absorption, long_decay_not_noise), vs scattering (the directional source's sparser early
// response: source_directivity) and vs a position error (position_error_0p1m) likewise.
INSTANTIATE_TEST_SUITE_P(
    Confounds, HiddenEffectTest,
    ::testing::Values(Case{"rolloff_50hz", {}, 31, rolloff(50.0), {"transducer_response"}},
                      Case{"rolloff_100hz", {}, 32, rolloff(100.0), {"transducer_response"}},
                      Case{"rolloff_200hz", {}, 33, rolloff(200.0), {"transducer_response"}},
                      Case{"position_error_0p1m", {}, 34, position_error(0.1)},
                      Case{"room_5pct_larger", {}, 35, size_error(0.05)},
                      Case{"room_5pct_smaller", {}, 36, size_error(-0.05)},
                      Case{"long_decay_not_noise", {"band_absorption"}, 37, long_decay()},
                      Case{"latency_not_alignment", {"time_offset"}, 38},
                      Case{"pre_alignment_not_latency", {}, 39, pre_aligned(5.0), std::set<std::string>(), {"time_offset"}},
                      // Files cut at 0.75 s and zero-padded to 1 s: digital silence is no noise floor
                      // and no 190 dB tail-level error.
                      Case{"silent_tail", {}, 40, silent_tail(0.25)}),
    case_name);

// Outside the catalog: what no effect names. The diagnosis must either name nothing or report the
// `unexplained` finding (which view departs from the extended model, where and how far), and never
// a catalog effect with a confident gain (its extension would send a user to fix the wrong thing).
// Where the departure is strong (a double slope, flutter: Case::also_expected = {"unexplained"})
// it must report it.
class OutOfCatalogTest : public ::testing::TestWithParam<Case> {};

TEST_P(OutOfCatalogTest, NamesNothingOrReportsUnexplainedNeverAWrongEffectWithAGain) {
  const Case& c = GetParam();
  const uint64_t seed = c.seed + 100 * seed_offset();
  const std::vector<sim::RoomSpec> rooms = testdata::make_test_rooms(kRirsPerSet, 77 + seed);
  const testdata::HiddenSet set = testdata::make_hidden_set(rooms, {}, seed, 16000.0, 1.0, c.options);
  diagnose::DiagnoseOptions options;
  options.num_threads = 2;
  const diagnose::Diagnosis d = diagnose::diagnose_set(set.stated, set.measured, options);
  std::cout << diagnose::diagnosis_summary(d) << "  unexplained: " << d.unexplained.evidence << "\n";
  for (const auto& [k, v] : set.truth) std::cout << "  truth " << k << " = " << v << "\n";
  bool named = false;
  for (const auto& f : d.findings) {
    if (!f.detected) continue;
    named = true;
    const bool confident_gain = f.held_out.rfind("confirmed", 0) == 0 || f.held_out.rfind("trade-off", 0) == 0;
    EXPECT_FALSE(confident_gain) << c.name << ": " << f.effect << " (" << f.held_out << "): " << f.evidence;
  }
  if (named || c.also_expected.count("unexplained")) {
    EXPECT_TRUE(d.unexplained.detected) << c.name << ": " << d.unexplained.evidence;
  }
}

testdata::HiddenOptions out_of_catalog(bool coupled, bool flutter, bool non_shoebox) {
  testdata::HiddenOptions o;
  o.coupled_room = coupled;
  o.flutter = flutter;
  o.non_shoebox = non_shoebox;
  return o;
}

INSTANTIATE_TEST_SUITE_P(
    OutOfCatalog, OutOfCatalogTest,
    ::testing::Values(Case{"coupled_room", {}, 41, out_of_catalog(true, false, false), {}, {"unexplained"}},
                      Case{"flutter_echo", {}, 42, out_of_catalog(false, true, false), {}, {"unexplained"}},
                      Case{"non_shoebox", {}, 43, out_of_catalog(false, false, true)}),
    case_name);

}  // namespace
}  // namespace tsrir
