// reverberate_stream() (long utterances, bounded memory) against reverberate_channel() (in
// memory) on the same inputs: the claim is the same output, so the comparison is exact. Chunks
// and I/O blocks are made tiny here so that a 5 s input crosses many chunk, block, noise wrap
// and tiling boundaries (1500-tap RIRs: 6693-sample engine blocks, two per chunk).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "augment/reverberate.h"
#include "augment/reverberate_stream.h"
#include "io/audio_io.h"
#include "reference_model.h"
#include "test_support.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace {

using reftest::Vec;
constexpr double kFs = 16000;

std::vector<float> to_float(const Vec& v) { return std::vector<float>(v.begin(), v.end()); }

struct Case {
  std::string name;
  std::vector<int> rirs;       // per output channel: index into rirs_, -1 = no RIR
  std::vector<reftest::Additive> additive;  // samples unused: noise index in `noises`
  std::vector<int> noises;     // per additive signal: index into noises_ (channel c uses noise + c)
  tsrir::ReverbOptions options;
  int input_channel = 0;
  size_t chunk_samples = 1;    // smallest: two engine blocks per call
};

class ReverberateStream : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tsrir_test::make_scratch_dir("stream").string();
    const Vec x = reftest::quantise16(reftest::speech_like(81617, kFs, 41));  // 5.1 s, odd length
    const Vec x2 = reftest::quantise16(reftest::speech_like(81617, kFs, 42));
    reftest::write_wav(dir_ + "/mono.wav", {x}, kFs, 16);
    reftest::write_wav(dir_ + "/stereo.wav", {x2, x}, kFs, 16);
    rirs_.push_back(to_float(reftest::synthetic_rir(1500, kFs, 120, 0.4, 43)));
    rirs_.push_back(to_float(reftest::synthetic_rir(1500, kFs, 210, 0.5, 44)));  // same length, other peak
    rirs_.push_back(to_float(reftest::synthetic_rir(40, kFs, 3, 0.01, 45)));     // engine's direct path
    for (uint64_t seed : {46, 47, 48}) noises_.push_back(to_float(reftest::noise_signal(9001, seed)));
    noises_.push_back(to_float(reftest::noise_signal(100000, 49)));  // longer than the speech
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  void check(const Case& c) {
    SCOPED_TRACE(c.name);
    const std::string input = dir_ + (c.input_channel == 0 ? "/mono.wav" : "/stereo.wav");
    tsrir::AudioInfo info;
    const std::vector<float> x = tsrir::read_audio_channels(input, &info).at(static_cast<size_t>(c.input_channel));
    std::vector<std::unique_ptr<tsrir::PreparedRir>> prepared;
    std::vector<tsrir::StreamChannel> channels(c.rirs.size());
    std::vector<std::vector<float>> want(c.rirs.size());
    for (size_t ch = 0; ch < c.rirs.size(); ++ch) {
      if (c.rirs[ch] >= 0) {
        prepared.push_back(std::make_unique<tsrir::PreparedRir>(rirs_[static_cast<size_t>(c.rirs[ch])], kFs));
        channels[ch].rir = prepared.back().get();
      }
      for (size_t i = 0; i < c.additive.size(); ++i) {
        tsrir::AdditiveSignal a;
        a.samples = std::make_shared<const std::vector<float>>(noises_.at(static_cast<size_t>(c.noises[i]) + ch));
        a.snr_db = c.additive[i].snr_db;
        a.start_time_s = c.additive[i].start_s;
        a.offset_s = c.additive[i].offset_s;
        channels[ch].additive.push_back(a);
      }
      want[ch] = tsrir::reverberate_channel(x, kFs, channels[ch].rir, channels[ch].additive, c.options);
    }
    tsrir::StreamSettings settings;
    settings.temp_base = dir_ + "/spill";
    settings.chunk_samples = c.chunk_samples;
    settings.block_frames = 777;
    settings.format = tsrir::SampleFormat::kFloat32;
    const std::string out = dir_ + "/out_" + c.name + ".wav";
    tsrir::StreamResult result =
        tsrir::reverberate_stream(input, "input", "", c.input_channel, channels, c.options, out, settings);
    ASSERT_EQ(result.frames, want[0].size());
    tsrir::AudioInfo out_info;
    const std::vector<std::vector<float>> got = tsrir::read_audio_channels(out, &out_info);
    ASSERT_EQ(got.size(), want.size());
    for (size_t ch = 0; ch < want.size(); ++ch) {
      ASSERT_EQ(got[ch].size(), want[ch].size()) << "channel " << ch;
      double peak = 0, worst = 0;
      size_t mismatches = 0;
      for (size_t i = 0; i < want[ch].size(); ++i) {
        peak = std::max(peak, std::abs(static_cast<double>(want[ch][i])));
        worst = std::max(worst, std::abs(static_cast<double>(got[ch][i]) - want[ch][i]));
        mismatches += got[ch][i] != want[ch][i];
      }
      // Correct to float rounding first: float32 FFT blocks cut elsewhere differ by up to
      // ~eps * log2(FFT size) ~ 1e-6 of the peak (7e-7 seen with chunks shifted off the engine's
      // grid); a misplaced noise sample, lost filter history or another gain is >= 1e-3...
      ASSERT_LE(worst, 4e-6 * std::max(peak, 1e-3)) << "channel " << ch;
      // ...and then the stronger claim: identical, as every step is the in-memory one.
      EXPECT_EQ(mismatches, 0u) << "channel " << ch << ": max |diff| " << worst;
    }
    // The 16-bit file as the programs write it: the same bytes as the in-memory encoder's.
    settings.format = tsrir::SampleFormat::kInt16;
    const std::string out16 = dir_ + "/out16_" + c.name + ".wav";
    tsrir::reverberate_stream(input, "input", "", c.input_channel, channels, c.options, out16, settings);
    std::ifstream f(out16, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(bytes == tsrir::encode_wav(want, kFs));
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "left behind: " << e.path();
  }

  std::string dir_;
  std::vector<std::vector<float>> rirs_, noises_;
};

tsrir::ReverbOptions options(bool shift, bool normalize, double volume = 0, double duration_s = 0) {
  tsrir::ReverbOptions o;
  o.shift_output = shift;
  o.normalize_output = normalize;
  o.volume = volume;
  o.duration_s = duration_s;
  return o;
}

TEST_F(ReverberateStream, OutputRulesMono) {
  check({"default", {0}, {}, {}, options(true, true)});
  check({"noshift", {0}, {}, {}, options(false, true)});
  check({"nonorm", {0}, {}, {}, options(true, false)});           // gain known: written directly
  check({"nonorm_noshift", {0}, {}, {}, options(false, false)});
  check({"volume", {0}, {}, {}, options(true, true, 0.7)});
  check({"shorter", {0}, {}, {}, options(true, true, 0, 1.7)});
  check({"tiled", {0}, {}, {}, options(true, true, 0, 12.23)});   // 2.4 times the input
  check({"tiled_noshift_volume", {0}, {}, {}, options(false, true, 1.3, 12.23)});
  check({"tiny_rir", {2}, {}, {}, options(true, true)});
  Case big_chunks{"big_chunks", {0}, {}, {}, options(true, true)};
  big_chunks.chunk_samples = 30000;
  check(big_chunks);
}

TEST_F(ReverberateStream, AdditiveSignals) {
  // Kaldi's: added once, from the start time, truncated; power over the signal's own length.
  check({"kaldi_noise", {0}, {{{}, 5, 0.4, 0.1}}, {0}, options(true, true)});
  check({"noise_no_rir", {-1}, {{{}, 2, 0.25, 0}}, {0}, options(true, true)});
  check({"start_after_end", {0}, {{{}, 5, 9.0, 0}}, {0}, options(true, true)});
  tsrir::ReverbOptions looped = options(true, true);
  looped.loop_additive_signals = true;
  check({"looped_two", {0}, {{{}, 3, 0.3, 0.21}, {{}, 10, 1.1, 0.47}}, {0, 1}, looped});
  check({"looped_long_noise", {0}, {{{}, 0, 0, 2.0}}, {3}, looped});
  check({"looped_no_rir", {-1}, {{{}, 1, 0.5, 0.3}}, {1}, looped});
  tsrir::ReverbOptions full = looped;
  full.snr_reference = tsrir::SnrReference::kFullReverb;
  check({"full_reference", {0}, {{{}, 4, 0, 0.6}}, {0}, full});
  full.duration_s = 11.1;
  full.normalize_output = false;
  check({"full_reference_tiled_nonorm", {0}, {{{}, 4, 0, 0.6}}, {2}, full});
}

TEST_F(ReverberateStream, MultiChannelAndInputChannel) {
  // One output channel per RIR, each with its own noise channel (noises_[k + c]).
  tsrir::ReverbOptions looped = options(true, true);
  looped.loop_additive_signals = true;
  check({"two_channels", {0, 1}, {{{}, 6, 0.2, 0.3}}, {0}, looped});
  check({"two_channels_noshift_tiled", {0, 1}, {}, {}, options(false, true, 0, 11.0)});
  looped.volume = 0.8;  // gain known: both channels written directly, interleaved as they come
  check({"two_channels_direct", {0, 1}, {{{}, 6, 0.2, 0.3}}, {0}, looped});
  Case second{"input_channel_1", {1}, {{{}, 6, 0.2, 0.3}}, {1}, looped};
  second.input_channel = 1;
  check(second);
}

// Errors are the in-memory path's, and leave no output and no temporaries.
TEST_F(ReverberateStream, ErrorsLeaveNothing) {
  const tsrir::PreparedRir rir(rirs_[0], kFs);
  tsrir::StreamChannel channel;
  channel.rir = &rir;
  tsrir::AdditiveSignal a;
  a.samples = std::make_shared<const std::vector<float>>(noises_[0]);
  a.offset_s = 5.0;  // beyond the 0.56 s noise, not looped
  channel.additive.push_back(a);
  tsrir::StreamSettings settings;
  settings.temp_base = dir_ + "/spill";
  const std::string out = dir_ + "/bad.wav";
  try {
    tsrir::reverberate_stream(dir_ + "/mono.wav", "input", "", 0, {channel}, {}, out, settings);
    ADD_FAILURE() << "no error for an offset beyond the signal";
  } catch (const tsrir::Error& e) {
    EXPECT_NE(std::string(e.what()).find("additive signal 1: offset 5 s is beyond its length"), std::string::npos)
        << e.what();
  }
  // A file whose data stops halfway through what its header announces.
  std::ifstream in(dir_ + "/mono.wav", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir_ + "/cut.wav", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  channel.additive.clear();
  EXPECT_THROW(tsrir::reverberate_stream(dir_ + "/cut.wav", "input", "", 0, {channel}, {}, out, settings),
               tsrir::Error);
  EXPECT_THROW(tsrir::reverberate_stream(dir_ + "/mono.wav", "input", "", 1, {channel}, {}, out, settings),
               tsrir::Error);  // no channel 1
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "left behind: " << e.path();
}

}  // namespace
