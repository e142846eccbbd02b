// Hide an effect, require finding it: for each case of the catalog (and some pairs) a "measured"
// set is generated with test-side formulations (hidden_effects.h); rir-diagnose must detect
// exactly the hidden effects (nothing in the null sets; 24 RIRs per set), and its extended model must reduce the
// held-out error of the metric the effect acts on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <set>
#include <string>

#include "diagnose/diagnose.h"
#include "hidden_effects.h"

namespace tsrir {
namespace {

// The held-out metric each extension must improve.
std::string metric_for(const std::string& effect) {
  if (effect == "room_modes") return "lf_spectral_distance";
  if (effect == "air_absorption" || effect == "band_absorption") return "t30_per_band";
  if (effect == "transducer_response") return "level_per_band";
  if (effect == "noise_floor") return "tail_level";
  if (effect == "diffuse_scattering") return "echo_density";
  return "onset";
}

struct Case {
  std::string name;
  std::set<std::string> hidden;
  uint64_t seed;
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

TEST_P(HiddenEffectTest, DetectsExactlyTheHiddenEffectsAndTheExtensionHelps) {
  const Case& c = GetParam();
  const uint64_t seed = c.seed + 100 * seed_offset();
  const std::vector<sim::RoomSpec> rooms = testing::make_test_rooms(24, 77 + seed);
  const testing::HiddenSet set = testing::make_hidden_set(rooms, c.hidden, seed);
  diagnose::DiagnoseOptions options;
  options.num_threads = 2;
  const diagnose::Diagnosis d = diagnose::diagnose_set(set.stated, set.measured, options);
  std::cout << diagnose::diagnosis_summary(d);
  for (const auto& f : d.findings) {
    if (f.detected != (c.hidden.count(f.effect) > 0)) std::cout << "  evidence " << f.effect << ": " << f.evidence << "\n";
    EXPECT_EQ(f.detected, c.hidden.count(f.effect) > 0) << c.name << ": " << f.effect << ": " << f.evidence;
    EXPECT_GE(f.confidence, 0.0);
    EXPECT_LE(f.confidence, 1.0);
  }
  for (const std::string& effect : c.hidden) {
    const std::string metric = metric_for(effect);
    bool found = false;
    for (const auto& g : d.gains) {
      if (g.name != metric) continue;
      found = true;
      // The extension must reduce the held-out error by more than its standard error: a gain
      // that noise could produce does not count.
      EXPECT_GT(g.gain, g.gain_se) << c.name << ": " << metric << " baseline " << g.baseline << " extended " << g.extended;
    }
    EXPECT_TRUE(found) << metric;
  }
  // Fitted parameters against the hidden truth, where the extension estimates the same quantity.
  for (const auto& f : d.findings) {
    if (!f.detected) continue;
    for (const auto& [name, value] : f.parameters) {
      if (f.effect == "time_offset" && name == "latency_ms" && set.truth.count("latency_ms")) {
        // Onsets are located to a fraction of a sample; 0.15 ms = 2.4 samples at 16 kHz.
        EXPECT_NEAR(value, set.truth.at("latency_ms"), 0.15);
      }
      if (f.effect == "diffuse_scattering" && name == "scattering" && set.truth.count("scattering")) {
        // Echo density saturates at high scattering, so its inversion is coarse there.
        EXPECT_NEAR(value, set.truth.at("scattering"), 0.25);
      }
    }
  }
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(
    Catalog, HiddenEffectTest,
    ::testing::Values(Case{"null_a", {}, 1}, Case{"null_b", {}, 2}, Case{"room_modes", {"room_modes"}, 3},
                      Case{"air_absorption", {"air_absorption"}, 4}, Case{"band_absorption", {"band_absorption"}, 5},
                      Case{"transducer_response", {"transducer_response"}, 6}, Case{"noise_floor", {"noise_floor"}, 7},
                      Case{"diffuse_scattering", {"diffuse_scattering"}, 8}, Case{"time_offset", {"time_offset"}, 9},
                      Case{"modes_and_noise", {"room_modes", "noise_floor"}, 10},
                      Case{"transducer_and_offset", {"transducer_response", "time_offset"}, 11},
                      Case{"air_and_scattering", {"air_absorption", "diffuse_scattering"}, 12}),
    case_name);

}  // namespace
}  // namespace tsrir
