// Probability rules, SNR specifications and the per-recording plan (no audio involved).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "augment/augment_plan.h"
#include "augment/sampling.h"
#include "util/error.h"

namespace {

TEST(Sampling, SetParameters) {
  auto a = tsrir::parse_set_parameters("0.5, RIRS_NOISES/simulated_rirs/smallroom/rir_list", "--rir-set-parameters");
  ASSERT_TRUE(a.weight.has_value());
  EXPECT_DOUBLE_EQ(*a.weight, 0.5);
  EXPECT_EQ(a.path, "RIRS_NOISES/simulated_rirs/smallroom/rir_list");
  auto b = tsrir::parse_set_parameters("noise_list", "--noise-set-parameters");
  EXPECT_FALSE(b.weight.has_value());
  EXPECT_THROW(tsrir::parse_set_parameters("x, ", "--rir-set-parameters"), tsrir::Error);
  EXPECT_THROW(tsrir::parse_set_parameters("abc, list", "--rir-set-parameters"), tsrir::Error);
}

TEST(Sampling, SetWeightsShareTheLeftover) {
  auto w = tsrir::resolve_set_weights({0.5, std::nullopt, std::nullopt}, "x");
  EXPECT_NEAR(w[0], 0.5, 1e-12);
  EXPECT_NEAR(w[1], 0.25, 1e-12);
  EXPECT_NEAR(w[2], 0.25, 1e-12);
  auto u = tsrir::resolve_set_weights({std::nullopt, std::nullopt}, "x");
  EXPECT_NEAR(u[0], 0.5, 1e-12);
  EXPECT_THROW(tsrir::resolve_set_weights({1.5, std::nullopt}, "x"), tsrir::Error);
  EXPECT_THROW(tsrir::resolve_set_weights({0.0}, "x"), tsrir::Error);
}

TEST(Sampling, ItemProbabilitiesWithSmoothing) {
  // Given 0.7 and two unspecified sharing 0.3; smoothing 0.3 towards 1/3 each.
  auto p = tsrir::item_probabilities({0.7, std::nullopt, std::nullopt}, 0.3, "list");
  EXPECT_NEAR(p[0], 0.7 * 0.7 + 0.1, 1e-12);
  EXPECT_NEAR(p[1], 0.7 * 0.15 + 0.1, 1e-12);
  EXPECT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-12);
  auto q = tsrir::item_probabilities({std::nullopt, std::nullopt}, 0.0, "list");
  EXPECT_NEAR(q[0], 0.5, 1e-12);
  EXPECT_THROW(tsrir::item_probabilities({}, 0.3, "list"), tsrir::Error);
}

TEST(Sampling, WeightedIndexFollowsWeights) {
  EXPECT_EQ(tsrir::weighted_index({1, 0, 3}, 0.0), 0u);
  EXPECT_EQ(tsrir::weighted_index({1, 0, 3}, 0.25), 2u);
  EXPECT_EQ(tsrir::weighted_index({1, 0, 3}, 0.9999999999), 2u);
  EXPECT_EQ(tsrir::weighted_index({0, 2, 0}, 0.5), 1u);
}

TEST(Sampling, SnrSpecs) {
  tsrir::Rng rng(1);
  auto range = tsrir::SnrSpec::parse("1:2", "--snrs");
  double lo = 10, hi = -10;
  for (int i = 0; i < 2000; ++i) {
    double v = range.draw(rng);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GE(lo, 1.0);
  EXPECT_LT(hi, 2.0);
  EXPECT_LT(lo, 1.01);  // 2000 uniform draws cover the range (P(miss) ~ e^-20)
  EXPECT_GT(hi, 1.99);
  auto list = tsrir::SnrSpec::parse("20,10,0", "--snrs");
  std::map<double, int> counts;
  for (int i = 0; i < 3000; ++i) counts[list.draw(rng)]++;
  EXPECT_EQ(counts.size(), 3u);
  for (auto& [v, c] : counts) EXPECT_NEAR(c, 1000, 120) << v;  // ~4.6 sd of a binomial(3000, 1/3)
  EXPECT_DOUBLE_EQ(tsrir::SnrSpec::parse("5", "--snrs").draw(rng), 5.0);
  EXPECT_THROW(tsrir::SnrSpec::parse("20:10:0", "--snrs"), tsrir::Error);  // Kaldi list syntax: say so
  EXPECT_THROW(tsrir::SnrSpec::parse("2:1", "--snrs"), tsrir::Error);
  EXPECT_THROW(tsrir::SnrSpec::parse("", "--snrs"), tsrir::Error);
}

tsrir::AugmentSources two_rooms() {
  tsrir::AugmentSources s;
  s.rirs = {{"a1", "A", "a1.wav", "l:1", 0.4}, {"a2", "A", "a2.wav", "l:2", 0.4}, {"b1", "B", "b1.wav", "l:3", 0.2}};
  s.noises = {{"isoA", "isotropic", "A", "isoA.wav", "n:1", 0.5}, {"ps", "point-source", "", "ps.wav", "n:2", 0.5}};
  return s;
}

std::map<std::string, std::string> many_recordings(int n) {
  std::map<std::string, std::string> scp;
  for (int i = 0; i < n; ++i) scp["utt" + std::to_string(100000 + i)] = "/data/" + std::to_string(i) + ".wav";
  return scp;
}

// Frequencies over 4000 recordings: binomial sd <= 0.008, tolerance 0.035 (> 4 sd).
TEST(Plan, DrawsFollowTheProbabilitiesAndRooms) {
  auto sources = two_rooms();
  tsrir::PlanOptions o;
  o.speech_rvb_probability = 0.5;
  o.noise_addition_probability = 0.8;
  auto plans = tsrir::plan_recordings(many_recordings(4000), sources, tsrir::SnrSpec::parse("1:2", "s"), o);
  ASSERT_EQ(plans.size(), 4000u);
  int rvb = 0, noise = 0, room_b = 0, iso_with_b = 0, iso_without_rir = 0;
  for (const auto& p : plans) {
    rvb += p.rir >= 0;
    noise += p.noise >= 0;
    if (p.rir >= 0 && sources.rirs[p.rir].room_id == "B") {
      ++room_b;
      iso_with_b += p.noise == 0;
    }
    if (p.rir < 0) iso_without_rir += p.noise == 0;
    if (p.noise >= 0) {
      EXPECT_GE(p.snr_db, 1.0);
      EXPECT_LE(p.snr_db, 2.0);
      EXPECT_GE(p.noise_offset_fraction, 0.0);
      EXPECT_LT(p.noise_offset_fraction, 1.0);
    }
  }
  EXPECT_NEAR(rvb / 4000.0, 0.5, 0.035);
  EXPECT_NEAR(noise / 4000.0, 0.8, 0.035);
  EXPECT_NEAR(room_b / double(rvb), 0.2, 0.035);
  EXPECT_EQ(iso_with_b, 0);       // isotropic noise of room A never with room B's RIRs
  EXPECT_EQ(iso_without_rir, 0);  // nor without any RIR
}

TEST(Plan, DeterministicPerRecordingAndIds) {
  auto sources = two_rooms();
  tsrir::PlanOptions o;
  o.random_seed = 3;
  o.num_replications = 2;
  o.include_original_data = true;
  o.prefix = "rvb";
  auto scp = many_recordings(50);
  auto plans = tsrir::plan_recordings(scp, sources, tsrir::SnrSpec::parse("0,5,10", "s"), o);
  ASSERT_EQ(plans.size(), 150u);
  EXPECT_EQ(plans[0].new_id, "rvb0-utt100000");
  EXPECT_FALSE(plans[0].modified());
  EXPECT_EQ(plans[50].new_id, "rvb1-utt100000");
  EXPECT_EQ(plans[149].new_id, "rvb2-utt100049");
  // A recording's draws do not depend on which other recordings exist.
  std::map<std::string, std::string> one = {{"utt100007", scp["utt100007"]}};
  auto single = tsrir::plan_recordings(one, sources, tsrir::SnrSpec::parse("0,5,10", "s"), o);
  EXPECT_EQ(single[1].rir, plans[57].rir);
  EXPECT_EQ(single[1].noise, plans[57].noise);
  EXPECT_EQ(single[1].snr_db, plans[57].snr_db);
  EXPECT_EQ(tsrir::copy_id("x", "", 1), "x");
  o.random_seed = 4;
  auto other = tsrir::plan_recordings(scp, sources, tsrir::SnrSpec::parse("0,5,10", "s"), o);
  int differ = 0;
  for (size_t i = 0; i < plans.size(); ++i) differ += plans[i].rir != other[i].rir || plans[i].snr_db != other[i].snr_db;
  EXPECT_GT(differ, 20);
}

TEST(Plan, PipeLineQuotesEverything) {
  auto sources = two_rooms();
  sources.rirs[0].rxfilename = "rirs/a 1;touch PWNED'.wav";
  tsrir::RecordingPlan p;
  p.source_rx = "/data/it's $(touch X).wav";
  p.rir = 0;
  p.noise = 1;
  p.snr_db = 1.25;
  p.noise_offset_s = 3.5;
  tsrir::PipeOptions o;
  o.program = "/opt/tsrir bin/wav-reverberate";
  const std::string line = tsrir::format_pipe(p, sources, o);
  EXPECT_EQ(line,
            "'/opt/tsrir bin/wav-reverberate' --shift-output=true "
            "'--impulse-response=rirs/a 1;touch PWNED'\\''.wav' --additive-signals=ps.wav --start-times=0 "
            "--snrs=1.25 --additive-offsets=3.5 --loop-additive-signals=true '/data/it'\\''s $(touch X).wav' - |");
  p.source_rx = "-rel.wav";
  EXPECT_NE(tsrir::format_pipe(p, sources, o).find(" ./-rel.wav - |"), std::string::npos);
  p.source_rx = "flac -c -d -s a.flac |";
  p.noise = -1;
  o.program = "wav-reverberate";
  EXPECT_EQ(tsrir::format_pipe(p, sources, o),
            "flac -c -d -s a.flac | wav-reverberate --shift-output=true '--impulse-response=rirs/a 1;touch "
            "PWNED'\\''.wav' - - |");
  sources.noises[1].rxfilename = "a,b.wav";
  p.noise = 1;
  EXPECT_THROW(tsrir::format_pipe(p, sources, o), tsrir::Error);
  p.rir = -1;
  p.noise = -1;
  EXPECT_EQ(tsrir::format_pipe(p, sources, o), p.source_rx);
}

}  // namespace
