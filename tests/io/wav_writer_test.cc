// The one WAV writer: int16 headers as libsndfile writes them (checked against libsndfile itself),
// float WAVs with the 18-byte fmt chunk and a fact chunk that sox reads without a warning, and
// encode_wav() = wav_header() + append_wav_frames() for any channel count.
#include "io/wav_writer.h"

#include <gtest/gtest.h>
#include <sndfile.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "io/audio_io.h"
#include "test_dir.h"

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
