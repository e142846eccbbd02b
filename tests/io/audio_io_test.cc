#include <gtest/gtest.h>
#include <sndfile.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "io/audio_io.h"
#include "io/rir_set.h"
#include "sndfile_writer.h"
#include "test_support.h"
#include "util/error.h"

using tsrir_test::TempDirTest;

using namespace tsrir;

namespace {

std::vector<float> sine(double f, double fs, size_t n, double amp = 0.5) {
  std::vector<float> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<float>(amp * std::sin(2 * M_PI * f * i / fs));
  return v;
}

void expect_error_mentions(const std::function<void()>& fn, const std::string& needle) {
  try {
    fn();
    FAIL() << "expected an error mentioning " << needle;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

class AudioIo : public TempDirTest {};

}  // namespace

TEST_F(AudioIo, ReadsEveryContainerAndSampleType) {
  auto left = sine(440, 16000, 4000), right = sine(1000, 16000, 4000, 0.25);
  struct Case {
    const char* name;
    int format;
    double tol;  // quantisation step of the encoding (lossy Vorbis: perceptual, checked loosely)
  };
  const Case cases[] = {{"a16.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 1.0 / 32768},
                        {"a24.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_24, 1e-6},
                        {"a32.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_32, 1e-8},
                        {"af.wav", SF_FORMAT_WAV | SF_FORMAT_FLOAT, 1e-7},
                        {"a.flac", SF_FORMAT_FLAC | SF_FORMAT_PCM_16, 1.0 / 32768},
                        {"a.ogg", SF_FORMAT_OGG | SF_FORMAT_VORBIS, 0.05}};
  for (const auto& c : cases) {
    write_with_sndfile(path(c.name), c.format, 16000, {left, right});
    AudioReadOptions o;
    o.channel = 1;
    Signal s = read_audio(path(c.name), o);
    EXPECT_EQ(s.sample_rate_hz, 16000) << c.name;
    ASSERT_EQ(s.size(), right.size()) << c.name;
    double max_err = 0;
    for (size_t i = 100; i < s.size() - 100; ++i) max_err = std::max(max_err, static_cast<double>(std::fabs(s.samples[i] - right[i])));
    EXPECT_LE(max_err, c.tol) << c.name;
  }
  AudioReadOptions mix;
  mix.channel = -1;
  Signal m = read_audio(path("af.wav"), mix);
  EXPECT_NEAR(m.samples[123], 0.5f * (left[123] + right[123]), 1e-6);
}

TEST_F(AudioIo, ResamplesWithSoxRate) {
  // A 1 kHz tone at 48 kHz -> 16 kHz must stay a 1 kHz tone of the same amplitude, aligned in time
  // (sox's linear-phase rate compensates its delay). -v quality: passband ripple << 0.01 dB.
  auto x = sine(1000, 48000, 48000);
  write_with_sndfile(path("t48.wav"), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 48000, {x});
  AudioReadOptions o;
  o.target_rate_hz = 16000;
  Signal s = read_audio(path("t48.wav"), o);
  EXPECT_EQ(s.sample_rate_hz, 16000);
  ASSERT_EQ(s.size(), 16000u);
  auto ref = sine(1000, 16000, 16000);
  double max_err = 0;
  for (size_t i = 500; i < 15500; ++i) max_err = std::max(max_err, static_cast<double>(std::fabs(s.samples[i] - ref[i])));
  EXPECT_LT(max_err, 1e-3);
  // Energy above the new Nyquist is removed: a 10 kHz tone vanishes at 16 kHz.
  auto hi = resample(sine(10000, 48000, 48000), 48000, 16000);
  double e = 0;
  for (size_t i = 500; i < 15500; ++i) e += hi[i] * hi[i];
  EXPECT_LT(std::sqrt(e / 15000), 1e-3);
}

TEST_F(AudioIo, WritesInt16AndFloatRoundTrip) {
  Signal s{"x", 16000, sine(300, 16000, 1600)};
  write_wav(path("o16.wav"), s);
  AudioWriteOptions fo;
  fo.format = SampleFormat::kFloat32;
  write_wav(path("of.wav"), s, fo);
  AudioInfo info;
  auto a = read_audio_channels(path("o16.wav"), &info);
  EXPECT_NE(info.format.find("16"), std::string::npos) << info.format;
  auto b = read_audio_channels(path("of.wav"), &info);
  EXPECT_NE(info.format.find("float"), std::string::npos) << info.format;
  for (size_t i = 0; i < s.size(); ++i) {
    ASSERT_NEAR(a[0][i], s.samples[i], 0.5 / 32768 + 1e-9);
    ASSERT_EQ(b[0][i], s.samples[i]);
  }
  long long clipped = -1;
  AudioWriteOptions co;
  co.clipped_samples = &clipped;
  write_wav(path("clip.wav"), Signal{"c", 16000, {0.5f, 1.5f, -2.0f}}, co);
  EXPECT_EQ(clipped, 2);
  EXPECT_THROW(write_wav(path("nan.wav"), Signal{"n", 16000, {0.5f, NAN}}), Error);
  EXPECT_FALSE(std::filesystem::exists(path("nan.wav")));
}

TEST_F(AudioIo, ClearErrorsForBadInput) {
  expect_error_mentions([&] { read_audio(path("missing.wav")); }, "missing.wav");
  write_text("garbage.wav", "this is not audio at all, just text........................");
  expect_error_mentions([&] { read_audio(path("garbage.wav")); }, "garbage.wav");
  // Truncated: header promises 4000 frames, file holds fewer.
  write_with_sndfile(path("full.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 16000, {sine(440, 16000, 4000)});
  std::filesystem::copy_file(path("full.wav"), path("trunc.wav"));
  std::filesystem::resize_file(path("trunc.wav"), 3000);
  expect_error_mentions([&] { read_audio(path("trunc.wav")); }, "truncated");
  // Zero-length.
  {
    SF_INFO info{};
    info.samplerate = 16000;
    info.channels = 1;
    info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
    sf_close(sf_open(path("empty.wav").c_str(), SFM_WRITE, &info));
  }
  expect_error_mentions([&] { read_audio(path("empty.wav")); }, "zero-length");
  // NaN samples.
  write_with_sndfile(path("nan.wav"), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 16000, {{0.1f, NAN, 0.2f}});
  expect_error_mentions([&] { read_audio(path("nan.wav")); }, "NaN");
  // Channel out of range, with the context (list line) in the message.
  AudioReadOptions o;
  o.channel = 3;
  o.context = "wav.scp:7";
  expect_error_mentions([&] { read_audio(path("full.wav"), o); }, "wav.scp:7");
}

TEST_F(AudioIo, PipesAreRunAndTheirFailuresReported) {
  write_with_sndfile(path("p.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 16000, {sine(440, 16000, 1000)});
  Signal s = read_audio("cat " + path("p.wav") + " |");
  EXPECT_EQ(s.size(), 1000u);
  expect_error_mentions([&] { read_audio("cat " + path("p.wav") + " && exit 3 |"); }, "exit status 3");
  expect_error_mentions([&] { read_audio("true |"); }, "empty input");
}

TEST_F(AudioIo, RirSetWriterIsAtomicAndWritesKaldiLists) {
  const std::string out = path("rirs");
  {
    RirSetWriter w(out, SampleFormat::kFloat32);
    w.add(Signal{"b", 16000, {1.0f, 0.5f}}, "room1");
    w.add(Signal{"a", 16000, {1.0f, 0.25f}});
    EXPECT_THROW(w.add(Signal{"a", 16000, {1.0f}}), Error);
    EXPECT_THROW(w.add(Signal{"x/y", 16000, {1.0f}}), Error);
    EXPECT_FALSE(std::filesystem::exists(out + "/a.wav"));  // nothing under the final name before commit
    EXPECT_FALSE(std::filesystem::exists(out + "/rir.scp"));
    w.commit();
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/a.wav"));
  auto refs = read_rir_refs(out + "/rir_list", nullptr);
  ASSERT_EQ(refs.size(), 2u);
  EXPECT_EQ(refs[0].id, "a");
  EXPECT_EQ(refs[1].room_id, "room1");
  Signal b = load_rir(refs[1]);
  EXPECT_EQ(b.samples[1], 0.5f);
  // Read without a ledger: nothing recorded, so the set may be replaced.
  { RirSetWriter(out, SampleFormat::kInt16); }
  // Read into the run's ledger: an input now, and no writer may write over it.
  auto scp = read_rir_refs(out + "/rir.scp", run_inputs());
  EXPECT_EQ(scp[0].rxfilename, refs[0].rxfilename);
  // The scp has no rooms: they come from the rir_list beside it.
  EXPECT_EQ(scp[1].room_id, "room1");
  EXPECT_EQ(scp[0].room_id, "a");
  EXPECT_THROW(RirSetWriter(out, SampleFormat::kInt16), Error);
  run_inputs()->clear();
  {
    RirSetWriter w(out, SampleFormat::kInt16);
    w.add(Signal{"c", 16000, {0.5f}});
    // Destroyed without commit: the previous complete set stays.
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/a.wav"));
  EXPECT_FALSE(std::filesystem::exists(out + "/c.wav"));
  for (const auto& e : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  // A single audio file is a set of one, id = file stem.
  auto one = read_rir_refs(out + "/a.wav", nullptr);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].id, "a");
}
