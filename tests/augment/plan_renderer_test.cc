// PlanRenderer's noise cache: a multichannel noise that serves both a recording without an array
// (its mono form, channel 0) and an array microphone (its own channel) is read once, its channels
// are handed out as they were read (no copy), and the "using channel 0" warning is given once.
#include "augment/plan_renderer.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/wav_writer.h"
#include "test_support.h"
#include "util/log.h"

namespace tsrir {
namespace {

TEST(PlanRenderer, ANoiseIsReadOnceForItsMonoAndItsPerMicrophoneForms) {
  tsrir_test::ScratchDir dir;
  // Two different channels of values a 16-bit WAV holds exactly (multiples of 1/256).
  std::vector<std::vector<float>> noise(2, std::vector<float>(800));
  for (size_t n = 0; n < noise[0].size(); ++n) {
    noise[0][n] = static_cast<float>(static_cast<int>(n % 50) - 25) / 256.0f;
    noise[1][n] = static_cast<float>(static_cast<int>((7 * n) % 31) - 15) / 256.0f;
  }
  write_wav_channels(dir.path("noise.wav"), noise, 16000);
  std::vector<std::vector<float>> rir(2, std::vector<float>(64, 0.0f));
  rir[0][3] = 1.0f;
  rir[1][5] = 0.5f;
  AudioWriteOptions float_wav;
  float_wav.format = SampleFormat::kFloat32;
  write_wav_channels(dir.path("array.wav"), rir, 16000, float_wav);

  AugmentSources sources;
  sources.rirs.push_back({"array", "room", dir.path("array.wav"), "rir_list:1", 1.0});
  NoiseChoice iso;
  iso.id = "iso";
  iso.noise_type = "isotropic";
  iso.room_linkage = "room";
  // A pipe that counts its runs: each read of the noise is one line in `runs`.
  iso.rxfilename = "echo read >> '" + dir.path("runs") + "'; cat '" + dir.path("noise.wav") + "' |";
  iso.where = "noise_list:1";
  sources.noises.push_back(iso);

  RecordingPlan mono;  // no RIR: the noise's mono form
  PlannedNoise planned;
  planned.noise = 0;
  planned.snr_db = 10;
  mono.noises.push_back(planned);
  RecordingPlan array = mono;  // microphone 1 of the array: the noise's channel 1
  array.rir = 0;

  std::vector<std::string> warnings;
  set_warning_handler([&](const std::string& m) { warnings.push_back(m); });
  PlanRenderer renderer(sources, ReverbOptions{});
  const std::vector<AdditiveSignal> first_mono = renderer.additive_signals(mono, 16000, -1);
  const std::vector<AdditiveSignal> mic1 = renderer.additive_signals(array, 16000, 1);
  const std::vector<AdditiveSignal> second_mono = renderer.additive_signals(mono, 16000, -1);
  set_warning_handler(nullptr);

  ASSERT_EQ(first_mono.size(), 1u);
  ASSERT_EQ(mic1.size(), 1u);
  ASSERT_EQ(second_mono.size(), 1u);
  EXPECT_EQ(*first_mono[0].samples, noise[0]);
  EXPECT_EQ(*mic1[0].samples, noise[1]);
  EXPECT_EQ(second_mono[0].samples.get(), first_mono[0].samples.get()) << "the mono form was copied";
  EXPECT_EQ(dir.read("runs"), "read\n") << "the noise was read more than once";
  EXPECT_EQ(warnings, std::vector<std::string>{"noise_list:1 (noise 'iso'): 2 channels; using channel 0"});
}

}  // namespace
}  // namespace tsrir
