// to_plan(): reverberate-data's options checked and turned into the plan, the one path the program
// and the Python Augmenter share; errors spell the option as the caller's user writes it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "augment/reverberate_data.h"
#include "test_support.h"
#include "util/error.h"

namespace tsrir {
namespace {

std::string error_of(const ReverberateDataOptions& o, OptionSpelling spelling) {
  try {
    to_plan(o, spelling);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ToPlan, ErrorsSpellTheOptionAsItsCallerDoes) {
  ReverberateDataOptions o;
  o.speech_rvb_probability = 1.5;
  EXPECT_EQ(error_of(o, OptionSpelling::kCommandLine), "--speech-rvb-probability must be in [0, 1]");
  EXPECT_EQ(error_of(o, OptionSpelling::kPython), "speech_rvb_probability must be in [0, 1]");
  o.speech_rvb_probability = 1.0;
  o.max_noises_per_recording = -1;
  EXPECT_EQ(error_of(o, OptionSpelling::kPython), "max_noises_per_recording cannot be negative");
  o.max_noises_per_recording = 0;
  EXPECT_EQ(error_of(o, OptionSpelling::kCommandLine),
            "nothing to apply: give --rir-set-parameters and/or --noise-set-parameters");
  EXPECT_EQ(error_of(o, OptionSpelling::kPython), "nothing to apply: give rir_set_parameters and/or noise_set_parameters");
}

TEST(ToPlan, TheOptionsBecomeThePlannersOptions) {
  tsrir_test::ScratchDir dir;
  const std::string list = dir.write("rir_list", "--rir-id a --room-id r1 a.wav\n--rir-id b --room-id r2 b.wav\n");
  ReverberateDataOptions o;
  o.rir_set_parameters = {list};
  o.num_replications = 2;
  o.speech_rvb_probability = 0.25;
  o.noise_start = NoiseStart::kRandom;
  o.point_source_noise_rir = PointSourceNoiseRir::kNone;
  o.max_noises_per_recording = 3;
  o.random_seed = 77;
  o.background_snrs = "1..2";
  o.reverb.shift_output = false;
  const ReverberatePlan plan = to_plan(o, OptionSpelling::kCommandLine);
  EXPECT_EQ(plan.sources.rirs.size(), 2u);
  EXPECT_EQ(plan.planning.prefix, "rvb");  // Kaldi's, for several copies
  EXPECT_EQ(plan.planning.num_replications, 2);
  EXPECT_EQ(plan.planning.speech_rvb_probability, 0.25);
  EXPECT_TRUE(plan.planning.noise.random_noise_start);
  EXPECT_FALSE(plan.planning.noise.point_source_noise_rir);
  EXPECT_EQ(plan.planning.noise.max_noises_per_recording, 3);
  EXPECT_EQ(plan.planning.random_seed, 77u);
  EXPECT_TRUE(plan.background_snrs.is_range());
  EXPECT_FALSE(plan.foreground_snrs.is_range());
  EXPECT_FALSE(plan.reverb.shift_output);
}

TEST(ToPlan, ChoicesHaveOneTableOfNames) {
  EXPECT_EQ(choice_name(noise_start_choices(), NoiseStart::kRandom), "random");
  EXPECT_EQ(choice_value(point_source_noise_rir_choices(), "same-room"), PointSourceNoiseRir::kSameRoom);
  EXPECT_THROW(choice_value(noise_start_choices(), "late"), Error);
}

}  // namespace
}  // namespace tsrir
