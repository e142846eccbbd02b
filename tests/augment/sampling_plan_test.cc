// Kaldi's reverberate_data_dir.py rules without audio: its probability formulas, SNR lists in cyclic
// order, and the per-recording plan (rooms, isotropic + point-source noises, foreground start times,
// noises per minute) checked against hand-worked cases and, over thousands of recordings, against
// the frequencies Kaldi's script documents. docs/kaldi-reverberation.md states each rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "augment/augment_plan.h"
#include "augment/augment_sources.h"
#include "augment/noise_type.h"
#include "augment/sampling.h"
#include "reference_model.h"
#include "test_support.h"
#include "util/error.h"

namespace {

using tsrir::PlannedNoise;
using tsrir::RecordingPlan;

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

TEST(Sampling, SetWeightsShareTheLeftoverAsKaldi) {
  auto w = tsrir::resolve_set_weights({0.5, std::nullopt, std::nullopt}, "x");
  EXPECT_NEAR(w[0], 0.5, 1e-12);
  EXPECT_NEAR(w[1], 0.25, 1e-12);
  EXPECT_NEAR(w[2], 0.25, 1e-12);
  // Kaldi: given weights reaching 1 leave 0 for the others (a warning), then normalise.
  auto over = tsrir::resolve_set_weights({1.5, std::nullopt}, "x");
  EXPECT_NEAR(over[0], 1.0, 1e-12);
  EXPECT_NEAR(over[1], 0.0, 1e-12);
  EXPECT_THROW(tsrir::resolve_set_weights({0.0}, "x"), tsrir::Error);
}

// Hand-worked from smooth_probability_distribution(): u = (1 - 0.6) / 2 = 0.2;
// given 0.6 -> 0.7 * 0.6 + 0.3 * 0.2 = 0.48; total 0.88.
TEST(Sampling, KaldiSmoothingFormula) {
  auto p = tsrir::kaldi_smoothed_probabilities({0.6, std::nullopt, std::nullopt}, 0.3, 1.0, "x");
  EXPECT_NEAR(p[0], 0.48 / 0.88, 1e-12);
  EXPECT_NEAR(p[1], 0.2 / 0.88, 1e-12);
  EXPECT_NEAR(p[2], 0.2 / 0.88, 1e-12);
  // All given: u = 0, so the smoothing only rescales (Kaldi's behaviour, not a mix with uniform).
  auto g = tsrir::kaldi_smoothed_probabilities({0.5, 0.25}, 0.3, 0.5, "x");
  EXPECT_NEAR(g[0], 0.5 * 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(g[1], 0.5 / 3.0, 1e-12);
  auto none = tsrir::kaldi_smoothed_probabilities({std::nullopt, std::nullopt, std::nullopt, std::nullopt}, 0.3, 1.0, "x");
  for (double v : none) EXPECT_NEAR(v, 0.25, 1e-12);
  EXPECT_THROW(tsrir::kaldi_smoothed_probabilities({0.0, 0.0}, 0.3, 1.0, "x"), tsrir::Error);
  EXPECT_THROW(tsrir::kaldi_smoothed_probabilities({0.5}, 1.5, 1.0, "x"), tsrir::Error);
}

TEST(Sampling, WeightedIndexFollowsWeights) {
  std::vector<double> w = {0.0, 1.0, 3.0};
  EXPECT_EQ(tsrir::weighted_index(w, 0.0), 1u);
  EXPECT_EQ(tsrir::weighted_index(w, 0.24), 1u);
  EXPECT_EQ(tsrir::weighted_index(w, 0.26), 2u);
  EXPECT_EQ(tsrir::weighted_index(w, 0.999999999), 2u);
}

TEST(Sampling, SnrSpellings) {
  // Kaldi's ':' is a list; our range is spelt with '..' so that no Kaldi string changes meaning.
  auto list = tsrir::SnrSpec::parse("20:10:15:5:0", "--foreground-snrs");
  EXPECT_FALSE(list.is_range());
  EXPECT_EQ(list.values(), (std::vector<double>{20, 10, 15, 5, 0}));
  auto two = tsrir::SnrSpec::parse("5:10", "--background-snrs");
  EXPECT_EQ(two.values(), (std::vector<double>{5, 10}));
  auto range = tsrir::SnrSpec::parse("-5..2.5", "--background-snrs");
  ASSERT_TRUE(range.is_range());
  EXPECT_EQ(range.lo(), -5.0);
  EXPECT_EQ(range.hi(), 2.5);
  EXPECT_EQ(tsrir::SnrSpec::parse("7", "s").values(), std::vector<double>{7});
  EXPECT_THROW(tsrir::SnrSpec::parse("20,10,0", "s"), tsrir::Error);
  EXPECT_THROW(tsrir::SnrSpec::parse("2..1", "s"), tsrir::Error);
  EXPECT_THROW(tsrir::SnrSpec::parse("", "s"), tsrir::Error);
  EXPECT_THROW(tsrir::SnrSpec::parse("1:x", "s"), tsrir::Error);
}

// list_cyclic_iterator: one shuffle, then the list over and over.
TEST(Sampling, SnrListsAreCycledInAShuffledOrder) {
  std::set<std::vector<double>> orders;
  for (uint64_t seed = 0; seed < 60; ++seed) {
    tsrir::SnrSequence seq(tsrir::SnrSpec::parse("20:10:0", "s"), tsrir::Rng(seed));
    tsrir::Rng unused(1);
    std::vector<double> first = {seq.next(unused), seq.next(unused), seq.next(unused)};
    std::vector<double> sorted = first;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::vector<double>{0, 10, 20}));  // a permutation
    for (int round = 0; round < 3; ++round)
      for (double v : first) EXPECT_EQ(seq.next(unused), v);  // then the same order again
    orders.insert(first);
  }
  EXPECT_EQ(orders.size(), 6u);  // every order occurs (P(miss one in 60) < 1e-4)
  tsrir::SnrSequence range(tsrir::SnrSpec::parse("1..2", "s"), tsrir::Rng(0));
  tsrir::Rng rng(5);
  for (int i = 0; i < 100; ++i) {
    double v = range.next(rng);
    EXPECT_GE(v, 1.0);
    EXPECT_LT(v, 2.0);
  }
}

// Room A: RIRs a1, a2 (0.4 each); room B: b1 (0.2). Isotropic noise isoA linked to A; point
// sources: background psb and foreground psf (0.5 each).
tsrir::AugmentSources two_rooms() {
  tsrir::AugmentSources s;
  s.rirs = {{"a1", "A", "a1.wav", "l:1", 0.4}, {"a2", "A", "a2.wav", "l:2", 0.4}, {"b1", "B", "b1.wav", "l:3", 0.2}};
  s.rirs_by_room = {{"A", {0, 1}}, {"B", {2}}};
  tsrir::NoiseChoice iso;
  iso.id = "isoA";
  iso.noise_type = "isotropic";
  iso.room_linkage = "A";
  iso.rxfilename = "isoA.wav";
  iso.probability = 1.0;
  tsrir::NoiseChoice psb;
  psb.id = "psb";
  psb.noise_type = "point-source";
  psb.rxfilename = "psb.wav";
  psb.probability = 0.5;
  tsrir::NoiseChoice psf = psb;
  psf.id = "psf";
  psf.bg_fg_type = tsrir::BgFgType::kForeground;
  psf.rxfilename = "psf.wav";
  s.noises = {iso, psb, psf};
  return s;
}

std::map<std::string, std::string> many_recordings(int n) {
  std::map<std::string, std::string> scp;
  for (int i = 0; i < n; ++i) scp["utt" + std::to_string(100000 + i)] = "/data/" + std::to_string(i) + ".wav";
  return scp;
}

std::map<std::string, double> durations(const std::map<std::string, std::string>& scp, double seconds) {
  std::map<std::string, double> d;
  for (const auto& [id, rx] : scp) d[id] = seconds;
  return d;
}

std::vector<RecordingPlan> plan(const tsrir::AugmentSources& s, const tsrir::PlanOptions& o, int n, double seconds,
                                const std::string& fg = "20:10:0", const std::string& bg = "20:10:0") {
  auto scp = many_recordings(n);
  return tsrir::plan_recordings(scp, durations(scp, seconds), s, tsrir::SnrSpec::parse(fg, "fg"),
                                tsrir::SnrSpec::parse(bg, "bg"), o);
}

// 4000 recordings of 90 s (max 3 point sources at 2 per minute). Frequencies are binomial: sd
// <= 0.008 for p over all recordings; tolerances are >= 4 sd of the subset they are taken over.
TEST(Plan, KaldiFrequenciesOverManyRecordings) {
  const auto sources = two_rooms();
  tsrir::PlanOptions o;
  o.speech_rvb_probability = 0.6;
  o.noise.isotropic_noise_addition_probability = 0.7;
  o.noise.pointsource_noise_addition_probability = 0.5;
  o.random_seed = 11;
  const auto plans = plan(sources, o, 4000, 90.0, "15:5", "20:10:0");
  int rvb = 0, room_a = 0, iso_in_a = 0, iso_in_a_unreverberated = 0, unreverberated_a = 0, with_ps = 0;
  std::map<int, int> ps_count;
  double fg_start_sum = 0;
  int fg = 0, fg_early = 0;
  for (const RecordingPlan& p : plans) {
    rvb += p.rir >= 0;
    if (p.rir >= 0) {
      EXPECT_EQ(sources.rirs[p.rir].room_id, p.room);
    }
    const bool in_a = p.room == "A";
    room_a += in_a;
    int iso = 0, ps = 0;
    for (const PlannedNoise& n : p.noises) {
      const auto& choice = sources.noises[n.noise];
      if (choice.noise_type == "isotropic") {
        ++iso;
        EXPECT_TRUE(in_a);  // only with its room
        EXPECT_EQ(n.rir, -1);  // recorded in the room: not convolved again
        EXPECT_EQ(n.extend_to_s, 90.0);
        EXPECT_EQ(n.start_time_s, 0.0);
        continue;
      }
      ++ps;
      ASSERT_GE(n.rir, 0);  // a point source through an RIR of the same room
      EXPECT_EQ(sources.rirs[n.rir].room_id, p.room);
      if (choice.bg_fg_type == tsrir::BgFgType::kForeground) {
        ++fg;
        EXPECT_EQ(n.extend_to_s, 0.0);  // added once, not extended
        EXPECT_GE(n.start_time_s, 0.0);
        EXPECT_LE(n.start_time_s, 90.0);
        EXPECT_NEAR(n.start_time_s * 100, std::round(n.start_time_s * 100), 1e-6);  // Kaldi's round(, 2)
        fg_start_sum += n.start_time_s;
        fg_early += n.start_time_s < 30.0;
        EXPECT_TRUE(n.snr_db == 15 || n.snr_db == 5);
      } else {
        EXPECT_EQ(n.extend_to_s, 90.0);
        EXPECT_EQ(n.start_time_s, 0.0);
        EXPECT_TRUE(n.snr_db == 20 || n.snr_db == 10 || n.snr_db == 0);
      }
    }
    if (iso) {  // Kaldi's order: isotropic first
      EXPECT_EQ(p.noises.front().noise, 0);
    }
    EXPECT_LE(iso, 1);
    iso_in_a += iso;
    if (in_a && p.rir < 0) {
      ++unreverberated_a;
      iso_in_a_unreverberated += iso;
    }
    with_ps += ps > 0;
    ++ps_count[ps];
  }
  EXPECT_NEAR(rvb / 4000.0, 0.6, 0.035);
  EXPECT_NEAR(room_a / 4000.0, 0.8, 0.035);
  EXPECT_NEAR(iso_in_a / double(room_a), 0.7, 0.035);
  // Kaldi keeps the isotropic noise for recordings left unreverberated (~1280 of them).
  EXPECT_NEAR(iso_in_a_unreverberated / double(unreverberated_a), 0.7, 0.06);
  EXPECT_NEAR(with_ps / 4000.0, 0.5, 0.035);
  EXPECT_EQ(ps_count.rbegin()->first, 3);  // floor(2 * 90 / 60)
  for (int k = 1; k <= 3; ++k) EXPECT_NEAR(ps_count[k] / double(with_ps), 1.0 / 3.0, 0.045);  // randint(1, 3)
  // Foreground starts uniform over the recording: mean 45 s (sd of the mean ~0.7 s), a third before 30 s.
  ASSERT_GT(fg, 1000);
  EXPECT_NEAR(fg_start_sum / fg, 45.0, 3.0);
  EXPECT_NEAR(fg_early / double(fg), 1.0 / 3.0, 0.05);
}

// The SNRs of each kind, read in plan order, are the shuffled list repeated (Kaldi's cyclic order).
TEST(Plan, SnrsFollowKaldisCyclicOrder) {
  const auto sources = two_rooms();
  tsrir::PlanOptions o;
  o.random_seed = 4;
  const auto plans = plan(sources, o, 500, 60.0, "15:5", "20:10:0:-5");
  std::vector<double> fg, bg;
  for (const RecordingPlan& p : plans)
    for (const PlannedNoise& n : p.noises) (n.foreground ? fg : bg).push_back(n.snr_db);
  ASSERT_GT(fg.size(), 50u);
  ASSERT_GT(bg.size(), 50u);
  for (size_t i = 2; i < fg.size(); ++i) EXPECT_EQ(fg[i], fg[i - 2]);
  for (size_t i = 4; i < bg.size(); ++i) EXPECT_EQ(bg[i], bg[i - 4]);
  std::vector<double> first(bg.begin(), bg.begin() + 4);
  std::sort(first.begin(), first.end());
  EXPECT_EQ(first, (std::vector<double>{-5, 0, 10, 20}));
}

TEST(Plan, NoisesPerMinuteAndExtensions) {
  const auto sources = two_rooms();
  tsrir::PlanOptions o;
  // Recordings under 30 s get no point-source noise at Kaldi's default 2 per minute.
  for (const RecordingPlan& p : plan(sources, o, 300, 29.0))
    for (const PlannedNoise& n : p.noises) EXPECT_EQ(sources.noises[n.noise].noise_type, "isotropic");
  o.noise.max_noises_per_minute = 0;
  for (const RecordingPlan& p : plan(sources, o, 50, 600.0))
    for (const PlannedNoise& n : p.noises) EXPECT_EQ(sources.noises[n.noise].noise_type, "isotropic");
  // Extensions: exactly one point source per recording, unreverberated, from a random offset, looped.
  o.noise.max_noises_per_recording = 1;
  o.noise.point_source_noise_rir = false;
  o.noise.random_noise_start = true;
  o.noise.isotropic_noise_addition_probability = 0.0;
  std::set<int> tenths;
  for (const RecordingPlan& p : plan(sources, o, 300, 12.0, "15:5", "1..2")) {
    ASSERT_EQ(p.noises.size(), 1u);
    const PlannedNoise& n = p.noises[0];
    EXPECT_EQ(n.rir, -1);
    if (!n.foreground) {
      EXPECT_TRUE(n.loop);
      EXPECT_EQ(n.extend_to_s, 0.0);
      EXPECT_GE(n.snr_db, 1.0);
      EXPECT_LE(n.snr_db, 2.0);
      tenths.insert(static_cast<int>(n.offset_fraction * 10));
    }
  }
  EXPECT_EQ(tenths.size(), 10u);
}

TEST(Plan, DeterministicPerRecordingAndIds) {
  const auto sources = two_rooms();
  tsrir::PlanOptions o;
  o.random_seed = 3;
  o.num_replications = 2;
  o.include_original_data = true;
  o.prefix = "rvb";
  auto scp = many_recordings(50);
  auto plans = tsrir::plan_recordings(scp, durations(scp, 70.0), sources, tsrir::SnrSpec::parse("0:5:10", "s"),
                                      tsrir::SnrSpec::parse("0:5:10", "s"), o);
  ASSERT_EQ(plans.size(), 150u);
  EXPECT_EQ(plans[0].new_id, "rvb0-utt100000");
  EXPECT_FALSE(plans[0].modified());
  EXPECT_EQ(plans[50].new_id, "rvb1-utt100000");
  EXPECT_EQ(plans[149].new_id, "rvb2-utt100049");
  // A recording's room, RIR and noises do not depend on which other recordings exist (only the
  // SNR lists are walked in order, as in Kaldi).
  std::map<std::string, std::string> one = {{"utt100007", scp["utt100007"]}};
  auto single = tsrir::plan_recordings(one, durations(one, 70.0), sources, tsrir::SnrSpec::parse("0:5:10", "s"),
                                       tsrir::SnrSpec::parse("0:5:10", "s"), o);
  EXPECT_EQ(single[1].rir, plans[57].rir);
  EXPECT_EQ(single[1].room, plans[57].room);
  ASSERT_EQ(single[1].noises.size(), plans[57].noises.size());
  for (size_t i = 0; i < single[1].noises.size(); ++i) {
    EXPECT_EQ(single[1].noises[i].noise, plans[57].noises[i].noise);
    EXPECT_EQ(single[1].noises[i].rir, plans[57].noises[i].rir);
    EXPECT_EQ(single[1].noises[i].start_time_s, plans[57].noises[i].start_time_s);
  }
  EXPECT_EQ(tsrir::copy_id("x", "", 1), "x");
}

TEST(Plan, PipesInKaldisForm) {
  auto sources = two_rooms();
  sources.rirs[0].rxfilename = "rirs/a 1;touch PWNED'.wav";
  RecordingPlan p;
  p.source_rx = "/data/it's $(touch X).wav";
  p.rir = 0;
  PlannedNoise iso;
  iso.noise = 0;
  iso.extend_to_s = 12.5;
  iso.snr_db = 10;
  PlannedNoise fg;
  fg.noise = 2;
  fg.rir = 1;
  fg.start_time_s = 3.25;
  fg.snr_db = 5;
  fg.foreground = true;
  p.noises = {iso, fg};
  tsrir::PipeOptions o;
  o.program = "/opt/tsrir bin/wav-reverberate";
  // Our program: the nested steps in its own process.
  EXPECT_EQ(tsrir::format_pipe(p, sources, o),
            "'/opt/tsrir bin/wav-reverberate' --shift-output=true "
            "'--impulse-response=rirs/a 1;touch PWNED'\\''.wav' --additive-signals=isoA.wav,psf.wav "
            "--start-times=0,3.25 --snrs=10,5 --additive-impulse-responses=,a2.wav --additive-durations=12.5,0 "
            "'/data/it'\\''s $(touch X).wav' - |");
  // Kaldi's program (or --pipe-dialect=kaldi): Kaldi's nested commands.
  o.tsrir_extensions = false;
  EXPECT_EQ(tsrir::format_pipe(p, sources, o),
            "'/opt/tsrir bin/wav-reverberate' --shift-output=true "
            "'--impulse-response=rirs/a 1;touch PWNED'\\''.wav' "
            "'--additive-signals='\\''/opt/tsrir bin/wav-reverberate'\\'' --duration=12.5 isoA.wav - |,"
            "'\\''/opt/tsrir bin/wav-reverberate'\\'' --impulse-response=a2.wav psf.wav - |' "
            "--start-times=0,3.25 --snrs=10,5 '/data/it'\\''s $(touch X).wav' - |");
  p.source_rx = "-rel.wav";
  EXPECT_NE(tsrir::format_pipe(p, sources, o).find(" ./-rel.wav - |"), std::string::npos);
  // A piped noise feeds the nested program through stdin, as Kaldi writes it.
  sources.noises[2].rxfilename = "sox psf.flac -t wav - |";
  o.program = "wav-reverberate";
  EXPECT_EQ(tsrir::noise_signal_rx(fg, sources, o.program),
            "sox psf.flac -t wav - | wav-reverberate --impulse-response=a2.wav - - |");
  // Looped noises (--noise-start=random) need our program's extension options.
  o.tsrir_extensions = true;
  p.noises = {iso};
  p.noises[0].extend_to_s = 0;
  p.noises[0].loop = true;
  p.noises[0].offset_s = 1.5;
  p.source_rx = "flac -c -d -s a.flac |";
  EXPECT_EQ(tsrir::format_pipe(p, sources, o),
            "flac -c -d -s a.flac | wav-reverberate --shift-output=true '--impulse-response=rirs/a 1;touch "
            "PWNED'\\''.wav' --additive-signals=isoA.wav --start-times=0 --snrs=10 --additive-offsets=1.5 "
            "--additive-loops=true - - |");
  o.tsrir_extensions = false;
  EXPECT_THROW(tsrir::format_pipe(p, sources, o), tsrir::Error);
  o.tsrir_extensions = true;
  sources.noises[0].rxfilename = "a,b.wav";
  EXPECT_THROW(tsrir::format_pipe(p, sources, o), tsrir::Error);
  p.rir = -1;
  p.noises.clear();
  EXPECT_EQ(tsrir::format_pipe(p, sources, o), p.source_rx);
}

// Lists as Kaldi reads them: duplicate ids across lists, the same list twice, an empty noise list,
// '#' lines; the noise probabilities per type.
class Lists : public ::testing::Test {
 protected:
  std::string dir;
  void SetUp() override { dir = tsrir_test::make_scratch_dir("lists").string(); }
  std::string put(const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  }
};

TEST_F(Lists, DuplicateIdsAndTheSameListTwiceAreKeptApart) {
  const std::string real = put("real", "--rir-id r1 --room-id A a.wav\n--rir-id r2 --room-id B b.wav\n");
  const std::string gas = put("gas", "--rir-id r1 --room-id A gas_a.wav\n--rir-id r2 --room-id B gas_b.wav\n");
  auto s = tsrir::load_augment_sources({"0.5, " + real, "0.5, " + gas}, {}, 0.3, 0.3);
  ASSERT_EQ(s.rirs.size(), 4u);
  EXPECT_EQ(s.rirs[0].rxfilename, "a.wav");
  EXPECT_EQ(s.rirs[2].rxfilename, "gas_a.wav");
  EXPECT_EQ(s.rirs_by_room.at("A"), (std::vector<size_t>{0, 2}));
  for (const auto& r : s.rirs) EXPECT_NEAR(r.probability, 0.25, 1e-12);
  auto twice = tsrir::load_augment_sources({real, real}, {}, 0.3, 0.3);
  EXPECT_EQ(twice.rirs.size(), 4u);
}

TEST_F(Lists, NoiseListsAsKaldiReadsThem) {
  const std::string rirs = put("rirs", "--rir-id r1 --room-id A a.wav\n--rir-id r2 --room-id B b.wav\n");
  const std::string empty = put("empty", "");
  auto s = tsrir::load_augment_sources({rirs}, {empty}, 0.3, 0.3);
  EXPECT_TRUE(s.noises.empty());  // Kaldi proceeds without noise
  // Refused with the list's file and line, and what is wrong.
  auto refused = [&](const std::string& list, const std::string& word) {
    try {
      tsrir::load_augment_sources({rirs}, {list}, 0.3, 0.3);
      return std::string("accepted");
    } catch (const tsrir::Error& e) {
      const std::string m = e.what();
      return m.find(list + ":1") != std::string::npos && m.find(word) != std::string::npos ? std::string("ok") : m;
    }
  };
  EXPECT_EQ(refused(put("commented", "# my noises\n--noise-id n1 --noise-type point-source n1.wav\n"), "comment"), "ok");
  EXPECT_EQ(refused(put("unknown", "--noise-id n1 --noise-type diffuse n1.wav\n"), "diffuse"), "ok");
  // Point sources: smoothed within their set, scaled by the set weight, normalised over all point
  // sources. Isotropic: per room, set weights and smoothing not applied.
  const std::string set1 = put("set1",
                               "--noise-id p1 --noise-type point-source --probability 0.6 p1.wav\n"
                               "--noise-id p2 --noise-type point-source p2.wav\n"
                               "--noise-id i1 --noise-type isotropic --room-linkage A --probability 0.2 i1.wav\n"
                               "--noise-id i2 --noise-type isotropic --room-linkage A i2.wav\n");
  const std::string set2 = put("set2", "--noise-id p3 --noise-type point-source p3.wav\n"
                                       "--noise-id i3 --noise-type isotropic --room-linkage B i3.wav\n");
  auto n = tsrir::load_augment_sources({rirs}, {"0.8, " + set1, set2}, 0.3, 0.3);
  std::map<std::string, double> p;
  for (const auto& c : n.noises) p[c.id] = c.probability;
  // set1: u = 0.4; p1 = 0.7 * 0.6 + 0.3 * 0.4 = 0.54, p2 = 0.4 -> scaled to 0.8: 0.4595, 0.3405;
  // set2 (weight 0.2): p3 = 0.2. Total 1.
  EXPECT_NEAR(p["p1"], 0.54 / 0.94 * 0.8, 1e-9);
  EXPECT_NEAR(p["p2"], 0.40 / 0.94 * 0.8, 1e-9);
  EXPECT_NEAR(p["p3"], 0.2, 1e-9);
  EXPECT_NEAR(p["i1"], 0.2, 1e-9);
  EXPECT_NEAR(p["i2"], 0.8, 1e-9);
  EXPECT_NEAR(p["i3"], 1.0, 1e-9);
}

}  // namespace
