// The one WAV writer: int16 headers as libsndfile writes them (checked against libsndfile itself),
// float WAVs with the 18-byte fmt chunk and a fact chunk that sox reads without a warning, and
// encode_wav() = wav_header() + append_wav_frames() for any channel count.
#include "io/wav_writer.h"

#include <gtest/gtest.h>
#include <sndfile.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "io/audio_io.h"
#include "util/error.h"
#include "test_support.h"

using tsrir_test::TempDirTest;

using namespace tsrir;

namespace {

class WavWriter : public TempDirTest {};

uint32_t u32_at(const std::string& b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}

std::string run_capturing_stderr(const std::string& command) {
  std::string out;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return "popen failed";
  char buf[512];
  while (fgets(buf, sizeof buf, p)) out += buf;
  pclose(p);
  return out;
}

std::vector<std::vector<float>> tones(int channels, size_t frames) {
  std::vector<std::vector<float>> ch(channels, std::vector<float>(frames));
  for (int c = 0; c < channels; ++c)
    for (size_t n = 0; n < frames; ++n) ch[c][n] = static_cast<float>(0.4 * std::sin(0.01 * (c + 1) * n));
  return ch;
}

}  // namespace

TEST_F(WavWriter, Int16HeaderIsLibsndfiles) {
  for (int channels : {1, 2}) {
    const auto ch = tones(channels, 1000);
    write_wav_channels(path("ours.wav"), ch, 16000);
    SF_INFO info{};
    info.samplerate = 16000;
    info.channels = channels;
    info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
    SNDFILE* f = sf_open(path("theirs.wav").c_str(), SFM_WRITE, &info);
    ASSERT_NE(f, nullptr);
    std::vector<short> zeros(1000 * channels, 0);
    sf_writef_short(f, zeros.data(), 1000);
    sf_close(f);
    const std::string ours = read_text("ours.wav"), theirs = read_text("theirs.wav");
    ASSERT_EQ(ours.size(), 44u + 2000u * channels);
    EXPECT_EQ(ours.substr(0, 44), theirs.substr(0, 44)) << channels << " channel(s)";
  }
}

TEST_F(WavWriter, FloatHasExtendedFmtAndFactChunkAndSoxReadsItWithoutWarning) {
  for (int channels : {1, 2, 3}) {
    const auto ch = tones(channels, 777);
    AudioWriteOptions o;
    o.format = SampleFormat::kFloat32;
    write_wav_channels(path("f.wav"), ch, 16000, o);
    const std::string b = read_text("f.wav");
    ASSERT_EQ(b.size(), 58u + 777u * 4 * channels);
    EXPECT_EQ(b.substr(0, 4), "RIFF");
    EXPECT_EQ(u32_at(b, 4), b.size() - 8);
    EXPECT_EQ(b.substr(12, 4), "fmt ");
    EXPECT_EQ(u32_at(b, 16), 18u);                                   // fmt chunk with cbSize
    EXPECT_EQ(static_cast<unsigned char>(b[20]), 3);                 // WAVE_FORMAT_IEEE_FLOAT
    EXPECT_EQ(b[36] | b[37], 0);                                     // cbSize = 0
    EXPECT_EQ(b.substr(38, 4), "fact");
    EXPECT_EQ(u32_at(b, 42), 4u);
    EXPECT_EQ(u32_at(b, 46), 777u);                                  // frames
    EXPECT_EQ(b.substr(50, 4), "data");
    EXPECT_EQ(u32_at(b, 54), 777u * 4 * channels);
    // libsndfile reads it back exactly.
    AudioInfo info;
    const auto back = read_audio_channels(path("f.wav"), &info);
    EXPECT_EQ(back, ch);
    // sox reads the same samples and does not warn.
    const std::string sox = run_capturing_stderr("sox '" + path("f.wav") + "' -n stat");
    EXPECT_EQ(sox.find("WARN"), std::string::npos) << sox;
    const size_t at = sox.find("Samples read:");
    ASSERT_NE(at, std::string::npos) << sox;
    EXPECT_EQ(std::stol(sox.substr(at + 13)), 777L * channels) << sox;
  }
}

TEST_F(WavWriter, EncodeIsHeaderPlusAppendedFramesForAnyChannelCount) {
  for (SampleFormat format : {SampleFormat::kInt16, SampleFormat::kFloat32}) {
    for (int channels : {1, 2, 5}) {
      const size_t frames = 9000;  // more than one interleaving block
      const auto ch = tones(channels, frames);
      AudioWriteOptions o;
      o.format = format;
      const std::vector<char> whole = encode_wav(ch, 16000, o);
      std::vector<char> pieces = wav_header(frames, channels, 16000, format);
      std::vector<float> inter;
      for (size_t n = 0; n < frames; ++n)
        for (int c = 0; c < channels; ++c) inter.push_back(ch[c][n]);
      long long clipped = 0;
      append_wav_frames(inter.data(), 5000, channels, format, 0, &pieces, &clipped);
      append_wav_frames(inter.data() + 5000 * channels, frames - 5000, channels, format, 5000, &pieces, &clipped);
      EXPECT_EQ(whole, pieces) << channels << " channel(s)";
    }
  }
}

// The two file modes write the same bytes (encode_wav's); kAtomic replaces the file by a rename (a
// new inode), kDirect writes into the path itself (the same inode, no temporary name beside it),
// and a kDirect write that cannot open its path names it.
TEST_F(WavWriter, DirectModeWritesInPlaceAtomicModeRenames) {
  const auto ch = tones(2, 1234);
  AudioWriteOptions o;
  o.format = SampleFormat::kFloat32;
  const std::vector<char> expected = encode_wav(ch, 16000, o);
  const std::string wav = path("m.wav");
  write_text("m.wav", "an older file");
  struct stat before {}, after {};
  ASSERT_EQ(::stat(wav.c_str(), &before), 0);
  o.file_mode = WavFileMode::kDirect;
  write_wav_channels(wav, ch, 16000, o);
  ASSERT_EQ(::stat(wav.c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino);
  EXPECT_EQ(read_text("m.wav"), std::string(expected.begin(), expected.end()));
  size_t entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir_)) entries += e.path().filename() == "m.wav" ? 0 : 1;
  EXPECT_EQ(entries, 0u) << "a direct write left another file beside it";

  o.file_mode = WavFileMode::kAtomic;
  write_wav_channels(wav, ch, 16000, o);
  ASSERT_EQ(::stat(wav.c_str(), &before), 0);
  EXPECT_NE(before.st_ino, after.st_ino);
  EXPECT_EQ(read_text("m.wav"), std::string(expected.begin(), expected.end()));

  o.file_mode = WavFileMode::kDirect;
  const std::string missing = path("no-such-dir/x.wav");
  try {
    write_wav_channels(missing, ch, 16000, o);
    FAIL() << "a direct write into a missing directory succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write " + missing), std::string::npos) << e.what();
  }
}

// 16-bit samples are round(v * 32768) half to even, clipped to [-32768, 32767] and counted when
// clipped: checked against std::nearbyint on ties, zeros, the clipping edges, huge values and a
// sweep of random ones (the writer rounds inline, not with nearbyint).
TEST(WavWriterRounding, Int16IsNearbyintThenClip) {
  std::vector<float> v = {0.0f, -0.0f, 1e-30f, -1e-30f, 0.5f / 32768, -0.5f / 32768, 1.5f / 32768, -1.5f / 32768,
                          2.5f / 32768, -2.5f / 32768, 32766.5f / 32768, -32767.5f / 32768, 32767.49f / 32768,
                          32767.5f / 32768, -32768.5f / 32768, 1.0f, -1.0f, 1.5f, -1.5f, 127.99f, -128.0f,
                          4194303.5f / 32768, 4194304.5f / 32768, 3e9f, -3e9f, 3e38f, -3e38f};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  for (int i = 0; i < 200000; ++i) v.push_back(u(rng));
  for (int i = -70000; i <= 70000; ++i) v.push_back((i + 0.5f) / 32768);  // every tie in range and past it
  long long clipped = 0;
  std::vector<char> bytes;
  append_wav_frames(v.data(), v.size(), 1, SampleFormat::kInt16, 0, &bytes, &clipped);
  ASSERT_EQ(bytes.size(), 2 * v.size());
  long long want_clipped = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    float r = std::nearbyint(v[i] * 32768.0f);
    if (r > 32767.0f || r < -32768.0f) ++want_clipped;
    const int want = static_cast<int>(std::clamp(r, -32768.0f, 32767.0f));
    const int got = static_cast<int16_t>(static_cast<uint16_t>(static_cast<unsigned char>(bytes[2 * i]) |
                                                                (static_cast<unsigned char>(bytes[2 * i + 1]) << 8)));
    ASSERT_EQ(got, want) << "sample " << v[i];
  }
  EXPECT_EQ(clipped, want_clipped);
}

// Float samples: the block path writes each sample's IEEE bytes, little-endian, as the per-sample
// path does (assembled here byte by byte from the bit pattern); a NaN or Inf hands the block back to
// the per-sample path, which names its frame and keeps the samples before it.
TEST(WavWriterRounding, FloatBlockIsTheSamplesBytesAndNonFiniteNamesItsFrame) {
  std::vector<float> v(64);
  for (size_t i = 0; i < v.size(); ++i) v[i] = std::ldexp(static_cast<float>(i) - 31.5f, -7) + 1e-30f;
  v[3] = -0.0f, v[4] = std::numeric_limits<float>::denorm_min(), v[5] = std::numeric_limits<float>::max();
  std::vector<char> bytes = {'x'};
  append_wav_frames(v.data(), v.size(), 1, SampleFormat::kFloat32, 0, &bytes, nullptr);
  ASSERT_EQ(bytes.size(), 1u + 4 * v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    uint32_t u;
    std::memcpy(&u, &v[i], 4);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(static_cast<unsigned char>(bytes[1 + 4 * i + k]), (u >> (8 * k)) & 0xff) << i;
  }
  for (float bad : {std::nanf(""), INFINITY, -INFINITY}) {
    std::vector<float> w = v;
    w[41] = bad;
    std::vector<char> out;
    try {
      append_wav_frames(w.data(), w.size(), 1, SampleFormat::kFloat32, 100, &out, nullptr);
      FAIL() << "no error for " << bad;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("NaN or Inf sample at frame 141"), std::string::npos) << e.what();
    }
    ASSERT_EQ(out.size(), 4u * 41);
    EXPECT_EQ(std::memcmp(out.data(), bytes.data() + 1, out.size()), 0);
  }
}

// A NaN or Inf sample is an error naming its frame, and the bytes appended before it stay, as
// written sample by sample (the int16 block path hands such a block back to the per-sample one).
TEST(WavWriterRounding, Int16NonFiniteNamesItsFrameAndKeepsWhatCameBefore) {
  for (float bad : {std::nanf(""), INFINITY, -INFINITY}) {
    std::vector<float> v(100);
    for (size_t i = 0; i < v.size(); ++i) v[i] = 0.001f * static_cast<float>(i) - 0.03f;
    v[57] = bad;
    std::vector<char> bytes = {'x', 'y'};  // what an earlier block left
    long long clipped = 7;
    try {
      append_wav_frames(v.data(), v.size() / 2, 2, SampleFormat::kInt16, 1000, &bytes, &clipped);
      FAIL() << "no error for " << bad;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("NaN or Inf sample at frame 1028"), std::string::npos) << e.what();
    }
    ASSERT_EQ(bytes.size(), 2u + 2 * 57);
    EXPECT_EQ(clipped, 7);
    for (size_t i = 0; i < 57; ++i) {
      const int got = static_cast<int16_t>(static_cast<uint16_t>(static_cast<unsigned char>(bytes[2 + 2 * i]) |
                                                                  (static_cast<unsigned char>(bytes[3 + 2 * i]) << 8)));
      EXPECT_EQ(got, static_cast<int>(std::nearbyint(v[i] * 32768.0f))) << i;
    }
  }
}
