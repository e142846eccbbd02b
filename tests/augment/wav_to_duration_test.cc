// wav-to-duration: Kaldi's contract (scp in, float archive out, exit codes) on files, pipes and
// formats Kaldi's reader lacks. Durations are checked against the sample counts written.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "augment/wav_duration.h"
#include "reference_model.h"
#include "test_support.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace {

const std::string kBin = std::string(TSRIR_BIN_DIR) + "/wav-to-duration";

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class WavToDuration : public ::testing::Test {
 protected:
  std::string dir;
  void SetUp() override {
    dir = tsrir_test::make_scratch_dir("w2d").string();
    reftest::write_wav(dir + "/a.wav", {reftest::Vec(19744, 0.1)}, 16000, 16);        // 1.234 s
    reftest::write_wav(dir + "/b f.wav", {reftest::Vec(4000, 0.1)}, 8000, 32, true);  // 0.5 s float
    reftest::write_wav(dir + "/c.wav", {reftest::Vec(44100 * 3, 0.1), reftest::Vec(44100 * 3, 0.0)}, 44100, 24);
    std::ofstream(dir + "/wav.scp") << "a " << dir << "/a.wav\n"
                                    << "b " << dir << "/b f.wav\n"  // Kaldi's scp: the rest of the line
                                    << "c cat " << dir << "/c.wav |\n";
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
};

TEST_F(WavToDuration, KaldisTextAndBinaryArchives) {
  ASSERT_EQ(run(kBin + " scp:" + dir + "/wav.scp ark,t:" + dir + "/reco2dur 2>/dev/null"), 0);
  // "<key> <float, 7 digits> \n", as Kaldi's BaseFloatWriter writes text.
  EXPECT_EQ(slurp(dir + "/reco2dur"), "a 1.234 \nb 0.5 \nc 3 \n");
  ASSERT_EQ(run(kBin + " --read-entire-file=true scp:" + dir + "/wav.scp ark:" + dir + "/bin.ark 2>/dev/null"), 0);
  const std::string bin = slurp(dir + "/bin.ark");
  ASSERT_EQ(bin.size(), 3 * 9u);  // "k " + "\0B" + "\4" + float32, per entry
  EXPECT_EQ(bin.substr(0, 5), std::string("a \0B\4", 5));
  float a = 0;
  std::memcpy(&a, bin.data() + 5, 4);
  EXPECT_FLOAT_EQ(a, 1.234f);
  // Kaldi's get_reco2dur.sh form through a pipe wspecifier.
  ASSERT_EQ(run(kBin + " scp:" + dir + "/wav.scp 'ark,t:| sort -r > " + dir + "/sorted' 2>/dev/null"), 0);
  EXPECT_EQ(slurp(dir + "/sorted"), "c 3 \nb 0.5 \na 1.234 \n");
}

TEST_F(WavToDuration, ExitCodesAndErrors) {
  std::ofstream(dir + "/empty.scp") << "";
  EXPECT_EQ(run(kBin + " scp:" + dir + "/empty.scp ark,t:- >/dev/null 2>&1"), 1);  // nothing printed
  EXPECT_EQ(run(kBin + " scp:" + dir + "/wav.scp >/dev/null 2>&1"), 1);             // one argument
  std::ofstream(dir + "/bad.scp") << "a " << dir << "/a.wav\nz " << dir << "/missing.wav\n";
  const std::string log = dir + "/log";
  EXPECT_EQ(run(kBin + " scp:" + dir + "/bad.scp ark,t:" + dir + "/out > " + log + " 2>&1"), 1);
  EXPECT_NE(slurp(log).find("bad.scp:2: recording 'z'"), std::string::npos) << slurp(log);
  EXPECT_FALSE(fs::exists(dir + "/out"));  // nothing half-written
  EXPECT_EQ(run(kBin + " ark:" + dir + "/wav.scp ark,t:- >/dev/null 2>&1"), 1);
  EXPECT_THROW(tsrir::parse_kaldi_specifier("wav.scp", "x"), tsrir::Error);
  EXPECT_THROW(tsrir::parse_kaldi_specifier("scp,q:wav.scp", "x"), tsrir::Error);
  EXPECT_TRUE(tsrir::parse_kaldi_specifier("ark,t:-", "x").has("t"));
}

// Pipes: the WAV header's data size when it states one (Kaldi's header-only reading), else the
// stream to its end (a streamed header from sox to a pipe).
TEST_F(WavToDuration, PipeHeadersAndStreamedWavs) {
  std::vector<char> header(44, 0);
  auto put32 = [&](size_t at, uint32_t v) { for (int i = 0; i < 4; ++i) header[at + i] = static_cast<char>(v >> (8 * i)); };
  std::memcpy(header.data(), "RIFF", 4);
  std::memcpy(header.data() + 8, "WAVEfmt ", 8);
  put32(16, 16);
  header[20] = 1;  // PCM
  header[22] = 2;  // channels
  put32(24, 8000);
  put32(28, 32000);
  header[32] = 4;  // block align
  header[34] = 16;
  std::memcpy(header.data() + 36, "data", 4);
  put32(40, 4 * 12000);  // 12000 frames at 8 kHz
  ASSERT_TRUE(tsrir::wav_header_duration_s(header).has_value());
  EXPECT_DOUBLE_EQ(*tsrir::wav_header_duration_s(header), 1.5);
  put32(40, 0xFFFFFFFFu);
  EXPECT_FALSE(tsrir::wav_header_duration_s(header).has_value());
  EXPECT_FALSE(tsrir::wav_header_duration_s(std::vector<char>(header.begin(), header.begin() + 20)).has_value());
  // A pipe whose header is streamed (written through a fifo-like cat of a truncated-size header):
  // read to the end gives the true length.
  std::ofstream(dir + "/streamed.scp") << "s sox " << dir << "/a.wav -t wav - |\n"
                                       << "h cat " << dir << "/a.wav |\n";
  ASSERT_EQ(run(kBin + " scp:" + dir + "/streamed.scp ark,t:" + dir + "/d 2>/dev/null"), 0);
  EXPECT_EQ(slurp(dir + "/d"), "s 1.234 \nh 1.234 \n");
}

}  // namespace
