// The plain-WAV reader against libsndfile itself: every layout it accepts must decode to exactly
// libsndfile's floats and description, and every layout it declines must still read (through
// libsndfile) as before. Files are written by libsndfile or byte by byte here, not by the reader.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <cstdint>
#include <cstring>
#include <random>

#include "io/audio_io.h"
#include "io/wav_reader.h"
#include "sndfile_writer.h"
#include "test_support.h"
#include "util/error.h"

using tsrir_test::TempDirTest;

using namespace tsrir;

namespace {

std::vector<std::vector<float>> random_channels(size_t channels, size_t frames, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<std::vector<float>> ch(channels, std::vector<float>(frames));
  for (auto& c : ch)
    for (float& v : c) v = u(rng);
  ch[0][0] = 1.0f;  // full scale both ways: the clipping ends of every encoding
  if (frames > 1) ch[0][1] = -1.0f;
  return ch;
}

// libsndfile's own reading: de-interleaved floats and "<major> <subtype>" names.
struct SndfileRead {
  std::vector<std::vector<float>> channels;
  AudioInfo info;
};
SndfileRead read_with_sndfile(const std::string& path) {
  SF_INFO sf{};
  SNDFILE* f = sf_open(path.c_str(), SFM_READ, &sf);
  EXPECT_NE(f, nullptr) << sf_strerror(nullptr);
  SndfileRead r;
  if (!f) return r;
  std::vector<float> inter(static_cast<size_t>(sf.frames * sf.channels));
  EXPECT_EQ(sf_readf_float(f, inter.data(), sf.frames), sf.frames);
  sf_close(f);
  r.channels.assign(static_cast<size_t>(sf.channels), std::vector<float>(static_cast<size_t>(sf.frames)));
  for (size_t n = 0; n < static_cast<size_t>(sf.frames); ++n)
    for (size_t c = 0; c < r.channels.size(); ++c) r.channels[c][n] = inter[n * r.channels.size() + c];
  SF_FORMAT_INFO fi;
  fi.format = sf.format & SF_FORMAT_TYPEMASK;
  sf_command(nullptr, SFC_GET_FORMAT_INFO, &fi, sizeof fi);
  r.info.format = fi.name;
  fi.format = sf.format & SF_FORMAT_SUBMASK;
  sf_command(nullptr, SFC_GET_FORMAT_INFO, &fi, sizeof fi);
  r.info.format += std::string(" ") + fi.name;
  r.info.sample_rate_hz = sf.samplerate;
  r.info.channels = sf.channels;
  r.info.frames = sf.frames;
  return r;
}

std::string bytes_of(const std::string& path) { return tsrir_test::slurp(path); }

void put_u32(std::string* s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_u16(std::string* s, uint16_t v) {
  s->push_back(static_cast<char>(v & 0xff));
  s->push_back(static_cast<char>(v >> 8));
}

// A 16-bit mono WAV assembled by hand, with the chunks given before the data.
std::string hand_made_wav(const std::vector<int16_t>& samples, const std::string& extra_chunks = "",
                          uint32_t data_size_field = 0xFFFFFFFFu) {
  std::string fmt;
  put_u16(&fmt, 1);
  put_u16(&fmt, 1);
  put_u32(&fmt, 16000);
  put_u32(&fmt, 32000);
  put_u16(&fmt, 2);
  put_u16(&fmt, 16);
  std::string data;
  for (int16_t v : samples) put_u16(&data, static_cast<uint16_t>(v));
  std::string body = "WAVEfmt ";
  put_u32(&body, 16);
  body += fmt + extra_chunks + "data";
  put_u32(&body, data_size_field == 0xFFFFFFFFu ? static_cast<uint32_t>(data.size()) : data_size_field);
  body += data;
  std::string file = "RIFF";
  put_u32(&file, static_cast<uint32_t>(body.size()));
  return file + body;
}

class WavReaderTest : public TempDirTest {};

TEST_F(WavReaderTest, AcceptedLayoutsDecodeExactlyAsLibsndfile) {
  struct Case {
    int format;
    size_t channels;
    int rate;
  };
  const int wav = SF_FORMAT_WAV, wavex = SF_FORMAT_WAVEX;
  const std::vector<Case> cases = {
      {wav | SF_FORMAT_PCM_16, 1, 16000},   {wav | SF_FORMAT_PCM_16, 2, 8000},
      {wav | SF_FORMAT_PCM_24, 1, 44100},   {wav | SF_FORMAT_PCM_32, 3, 48000},
      {wav | SF_FORMAT_FLOAT, 1, 16000},    {wav | SF_FORMAT_FLOAT, 2, 22050},
      {wavex | SF_FORMAT_PCM_16, 6, 16000}, {wavex | SF_FORMAT_PCM_24, 2, 96000},
      {wavex | SF_FORMAT_PCM_32, 1, 16000}, {wavex | SF_FORMAT_FLOAT, 4, 16000},
  };
  unsigned seed = 1;
  for (const Case& c : cases) {
    SCOPED_TRACE("format " + std::to_string(c.format) + ", " + std::to_string(c.channels) + " channels");
    const std::string p = path("a" + std::to_string(seed) + ".wav");
    write_with_sndfile(p, c.format, c.rate, random_channels(c.channels, 3001, seed++));
    const std::string file = bytes_of(p);
    PlainWavLayout layout;
    ASSERT_TRUE(parse_plain_wav(file.data(), file.size(), &layout));
    const SndfileRead want = read_with_sndfile(p);
    std::vector<std::vector<float>> got;
    decode_plain_wav(file.data(), layout, 0, layout.frames, p, &got);
    ASSERT_EQ(got.size(), want.channels.size());
    for (size_t ch = 0; ch < got.size(); ++ch) {
      ASSERT_EQ(got[ch].size(), want.channels[ch].size());
      // Bit for bit, not approximately: the reader replaces libsndfile on these files.
      EXPECT_EQ(std::memcmp(got[ch].data(), want.channels[ch].data(), got[ch].size() * sizeof(float)), 0)
          << "channel " << ch;
    }
    EXPECT_EQ(layout.format_name(), want.info.format);
    // The public entry points take this path for files, pipes' bytes and headers alike.
    AudioInfo info;
    EXPECT_EQ(read_audio_channels(p, &info), want.channels);
    EXPECT_EQ(info.format, want.info.format);
    EXPECT_EQ(info.frames, want.info.frames);
    EXPECT_EQ(info.channels, want.info.channels);
    EXPECT_EQ(info.sample_rate_hz, want.info.sample_rate_hz);
    EXPECT_EQ(decode_audio_bytes(std::vector<char>(file.begin(), file.end()), &info, "bytes"), want.channels);
    EXPECT_EQ(probe_audio(p).format, want.info.format);
  }
}

TEST_F(WavReaderTest, PrefixOfIntegerPcmIsTheWholeReadCut) {
  const std::string p = path("long.wav");
  write_with_sndfile(p, SF_FORMAT_WAV | SF_FORMAT_PCM_16, 16000, random_channels(2, 5000, 9));
  AudioInfo whole_info, prefix_info;
  std::vector<std::vector<float>> whole = read_audio_channels(p, &whole_info);
  std::vector<std::vector<float>> prefix = read_audio_channels_prefix(p, 1234, &prefix_info);
  ASSERT_EQ(prefix.size(), 2u);
  for (size_t c = 0; c < 2; ++c)
    EXPECT_EQ(prefix[c], std::vector<float>(whole[c].begin(), whole[c].begin() + 1234));
  EXPECT_EQ(prefix_info.frames, 5000);  // the file's length, not the prefix's
  EXPECT_EQ(read_audio_channels_prefix(p, 99999, &prefix_info), whole);
}

TEST_F(WavReaderTest, UnusualFilesAreLeftToLibsndfile) {
  const std::vector<int16_t> samples = {1, -2, 300, -32768, 32767, 0, 7};
  struct Case {
    std::string name;
    std::string bytes;
  };
  std::string junk_odd = "JUNK";
  put_u32(&junk_odd, 3);
  junk_odd += std::string("abc") + '\0';  // odd-sized chunk and its pad byte: still plain
  std::string unknown = "abcd";
  put_u32(&unknown, 2);
  unknown += "xy";
  std::vector<Case> declined = {
      {"data size beyond the file (truncated)", hand_made_wav(samples, "", 1000)},
      {"a partial last frame", hand_made_wav(samples, "", 13)},
      {"an unknown chunk before the data", hand_made_wav(samples, unknown)},
  };
  std::string rifx = hand_made_wav(samples);
  rifx[3] = 'X';
  declined.push_back({"RIFX (big-endian)", rifx});
  std::string eight_bit = hand_made_wav(samples);
  eight_bit[34] = 8;  // bits per sample
  declined.push_back({"8-bit", eight_bit});
  for (const Case& c : declined) {
    SCOPED_TRACE(c.name);
    PlainWavLayout layout;
    EXPECT_FALSE(parse_plain_wav(c.bytes.data(), c.bytes.size(), &layout));
  }
  // Accepted: a passive chunk of odd size before the data.
  const std::string plain = hand_made_wav(samples, junk_odd);
  PlainWavLayout layout;
  ASSERT_TRUE(parse_plain_wav(plain.data(), plain.size(), &layout));
  EXPECT_EQ(layout.frames, samples.size());
  // A declined file still reads as libsndfile reads it, with libsndfile's verdict.
  write_text("truncated.wav", declined[0].bytes);
  EXPECT_THROW(read_audio_channels(path("truncated.wav"), nullptr), Error);
  write_text("unknown_chunk.wav", declined[2].bytes);
  AudioInfo info;
  const auto channels = read_audio_channels(path("unknown_chunk.wav"), &info);
  ASSERT_EQ(channels.size(), 1u);
  ASSERT_EQ(channels[0].size(), samples.size());
  for (size_t i = 0; i < samples.size(); ++i) EXPECT_EQ(channels[0][i], samples[i] / 32768.0f);
}

TEST_F(WavReaderTest, NanInFloatWavIsAnError) {
  const std::string p = path("nan.wav");
  std::vector<std::vector<float>> ch = random_channels(1, 100, 3);
  ch[0][57] = std::nanf("");
  write_with_sndfile(p, SF_FORMAT_WAV | SF_FORMAT_FLOAT, 16000, ch);
  try {
    read_audio_channels(p, nullptr);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("NaN or Inf sample at frame 57"), std::string::npos) << e.what();
  }
}

}  // namespace
