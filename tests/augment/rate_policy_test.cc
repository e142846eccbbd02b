// No silent rate or channel changes (issue 32): reverberate-data refuses a recording at another
// rate than the data dir's unless --sample-rate asks for that rate (then it resamples, in wavs and in
// pipes alike), validate-data-dir reports mixed rates, a multichannel input without a channel
// choice gets a one-line warning naming the channel used, and wav-to-duration reads a flac pipe to
// its end (flac then reports no error). The test signals are sums of sines defined analytically at
// each rate (not made by the resampler under test).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "io/audio_io.h"
#include "reference_model.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace {

const std::string kBin = std::string(TSRIR_BIN_DIR) + "/";

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// A 1.5 s band-limited signal (partials below 4 kHz, so identical in content at 16 and 48 kHz).
reftest::Vec tones(double fs, double seconds = 1.5) {
  reftest::Vec x(static_cast<size_t>(std::lround(seconds * fs)));
  for (size_t n = 0; n < x.size(); ++n) {
    const double t = n / fs;
    x[n] = 0.2 * std::sin(2 * M_PI * 220 * t) + 0.1 * std::sin(2 * M_PI * 1330 * t + 0.3) +
           0.05 * std::sin(2 * M_PI * 3100 * t + 1.1);
  }
  return x;
}

class RatePolicy : public ::testing::Test {
 protected:
  std::string dir;
  std::string log;

  void SetUp() override {
    dir = tsrir_test::make_scratch_dir("rate_policy").string();
    log = dir + "/log";
    reftest::write_wav(dir + "/a16.wav", {tones(16000)}, 16000, 16);
    reftest::write_wav(dir + "/b48.wav", {tones(48000)}, 48000, 16);
    reftest::write_wav(dir + "/st16.wav", {tones(16000), reftest::Vec(24000, 0.0)}, 16000, 16);
    reftest::write_wav(dir + "/rir.wav", {reftest::synthetic_rir(4000, 16000, 100, 0.3, 7)}, 16000, 32, true);
    reftest::write_wav(dir + "/rir_st.wav",
                       {reftest::synthetic_rir(4000, 16000, 100, 0.3, 7), reftest::synthetic_rir(4000, 16000, 90, 0.3, 8)},
                       16000, 32, true);
    std::ofstream(dir + "/rir_list") << "--rir-id r1 --room-id room1 " << dir << "/rir.wav\n";
    make_dir("mixed", {{"a", dir + "/a16.wav"}, {"b", dir + "/b48.wav"}});
    make_dir("stereo", {{"s", dir + "/st16.wav"}});
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir);
  }
  void make_dir(const std::string& name, const std::vector<std::pair<std::string, std::string>>& recordings) {
    fs::create_directories(dir + "/" + name);
    std::ofstream wav(dir + "/" + name + "/wav.scp"), utt2spk(dir + "/" + name + "/utt2spk"),
        spk2utt(dir + "/" + name + "/spk2utt");
    for (const auto& [id, rx] : recordings) {
      wav << id << " " << rx << "\n";
      utt2spk << id << " " << id << "\n";
      spk2utt << id << " " << id << "\n";
    }
  }
  // Runs a program; stderr and stdout go to `log`.
  int run(const std::string& args) {
    const int status = std::system(("cd " + dir + " && " + args + " > " + log + " 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string reverberate_data(const std::string& extra, const std::string& in, const std::string& out) {
    return kBin + "reverberate-data --rir-set-parameters rir_list --random-seed 3 " + extra + " " + in + " " + out;
  }
};

TEST_F(RatePolicy, AMixedRateDataDirIsRefusedWithoutSampleRate) {
  for (const std::string mode : {"--write-wavs wavs", ""}) {
    SCOPED_TRACE(mode.empty() ? "pipes" : mode);
    EXPECT_EQ(run(reverberate_data(mode, "mixed", "out")), 1);
    const std::string text = slurp(log);
    EXPECT_NE(text.find("recording 'b': recorded at 48000 Hz, but the data dir's rate is 16000 Hz"), std::string::npos)
        << text;
    EXPECT_NE(text.find("--sample-rate=16000"), std::string::npos) << text;
    EXPECT_FALSE(fs::exists(dir + "/out"));
  }
}

TEST_F(RatePolicy, SampleRateResamplesEveryRecordingInWavsAndPipesAlike) {
  ASSERT_EQ(run(reverberate_data("--sample-rate 16000 --write-wavs wavs", "mixed", "out_wavs")), 0) << slurp(log);
  tsrir::AudioInfo a_info, b_info;
  const auto a = tsrir::read_audio_channels(dir + "/wavs/a.wav", &a_info);
  const auto b = tsrir::read_audio_channels(dir + "/wavs/b.wav", &b_info);
  EXPECT_EQ(b_info.sample_rate_hz, 16000);
  ASSERT_EQ(b[0].size(), a[0].size());  // 1.5 s at 16 kHz either way
  // The same tones through the same RIR: the 48 kHz recording, resampled, gives the 16 kHz one's
  // output up to the resampler's band edge error (the tones are far below it).
  double num = 0, den = 0;
  for (size_t n = 2000; n + 2000 < a[0].size(); ++n) {
    num += (a[0][n] - b[0][n]) * (a[0][n] - b[0][n]);
    den += a[0][n] * a[0][n];
  }
  EXPECT_LT(10 * std::log10(num / den), -40) << "resampled recording differs from the native-rate one";

  // Pipes: --sample-rate goes into each pipe, and the pipe gives the wav written above.
  ASSERT_EQ(run(reverberate_data("--sample-rate=16000", "mixed", "out_pipes")), 0) << slurp(log);
  const std::string scp = slurp(dir + "/out_pipes/wav.scp");
  EXPECT_NE(scp.find("--sample-rate=16000"), std::string::npos) << scp;
  std::istringstream lines(scp);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("b ", 0) != 0) continue;
    const std::string pipe = line.substr(2, line.size() - 2 - 1);  // without the key and '|'
    ASSERT_EQ(std::system(("cd " + dir + " && " + pipe + " > piped_b.wav 2>" + log).c_str()), 0) << slurp(log);
  }
  tsrir::AudioInfo piped_info;
  EXPECT_EQ(tsrir::read_audio_channels(dir + "/piped_b.wav", &piped_info), b);
  EXPECT_EQ(piped_info.sample_rate_hz, 16000);
}

TEST_F(RatePolicy, KaldisPipeProgramCannotResampleSoTheRecordingIsRefused) {
  EXPECT_EQ(run(reverberate_data("--sample-rate 16000 --pipe-dialect kaldi", "mixed", "out")), 1);
  EXPECT_NE(slurp(log).find("cannot resample it"), std::string::npos) << slurp(log);
}

TEST_F(RatePolicy, ValidateDataDirReportsMixedRates) {
  EXPECT_EQ(run(kBin + "validate-data-dir --no-text mixed"), 1);
  const std::string text = slurp(log);
  EXPECT_NE(text.find("mixed sample rates: 16000 Hz (1 recording(s), e.g. 'a') 48000 Hz (1 recording(s), e.g. 'b')"),
            std::string::npos)
      << text;
  EXPECT_EQ(run(kBin + "validate-data-dir --no-text --check-rates=false mixed"), 0) << slurp(log);
  EXPECT_EQ(run(kBin + "validate-data-dir --no-text stereo"), 0) << slurp(log);
  // A recording that cannot be read (a dir made on another machine) is left out of the rate check,
  // as Kaldi's checks are of the tables: the readable ones still disagree, and alone one is valid.
  make_dir("elsewhere", {{"a", dir + "/a16.wav"}, {"b", dir + "/b48.wav"}, {"c", "/nonexistent/c.wav"}});
  EXPECT_EQ(run(kBin + "validate-data-dir --no-text elsewhere"), 1);
  EXPECT_NE(slurp(log).find("mixed sample rates"), std::string::npos) << slurp(log);
  make_dir("one_readable", {{"a", dir + "/a16.wav"}, {"c", "/nonexistent/c.wav"}});
  EXPECT_EQ(run(kBin + "validate-data-dir --no-text one_readable"), 0) << slurp(log);
  EXPECT_NE(slurp(log).find("1 recording(s) could not be read: their rates are not checked"), std::string::npos)
      << slurp(log);
}

TEST_F(RatePolicy, AMultichannelInputWithoutAChannelChoiceIsNamedInOneWarning) {
  ASSERT_EQ(run(reverberate_data("--write-wavs wavs_st", "stereo", "out_st")), 0) << slurp(log);
  EXPECT_NE(slurp(log).find("stereo/wav.scp: recording 's': 2 channels; using channel 0"), std::string::npos)
      << slurp(log);

  const std::string wr = kBin + "wav-reverberate --impulse-response=";
  ASSERT_EQ(run(wr + "rir.wav st16.wav o1.wav"), 0);
  EXPECT_NE(slurp(log).find("WARNING: input: 2 channels; using channel 0 (--input-wave-channel chooses)"),
            std::string::npos)
      << slurp(log);
  ASSERT_EQ(run(wr + "rir.wav --input-wave-channel=0 st16.wav o2.wav"), 0);
  EXPECT_EQ(slurp(log).find("WARNING"), std::string::npos) << slurp(log);
  ASSERT_EQ(run(wr + "rir_st.wav a16.wav o3.wav"), 0);
  EXPECT_NE(slurp(log).find("--impulse-response: 2 channels; using channel 0 (--rir-channel chooses)"),
            std::string::npos)
      << slurp(log);
  ASSERT_EQ(run(wr + "rir_st.wav --rir-channel=1 a16.wav o4.wav"), 0);
  EXPECT_EQ(slurp(log).find("WARNING"), std::string::npos) << slurp(log);
}

TEST_F(RatePolicy, WavReverberateSampleRateResamplesItsInput) {
  ASSERT_EQ(run(kBin + "wav-reverberate --sample-rate=16000 --impulse-response=rir.wav b48.wav o.wav"), 0) << slurp(log);
  tsrir::AudioInfo info;
  const auto out = tsrir::read_audio_channels(dir + "/o.wav", &info);
  EXPECT_EQ(info.sample_rate_hz, 16000);
  EXPECT_EQ(out[0].size(), 24000u);
  ASSERT_EQ(run(kBin + "wav-reverberate --impulse-response=rir.wav b48.wav o48.wav"), 0);
  EXPECT_EQ(tsrir::probe_audio(dir + "/o48.wav").sample_rate_hz, 48000);  // no option: the input's rate
}

TEST_F(RatePolicy, DurationProbeReadsAFlacPipeToItsEnd) {
  if (std::system("command -v flac >/dev/null && command -v sox >/dev/null") != 0)
    GTEST_SKIP() << "flac or sox not installed";
  // 5 s: the decoded stream (160 KB) is longer than the 64 KB header read.
  reftest::write_wav(dir + "/long.wav", {tones(16000, 5.0)}, 16000, 16);
  ASSERT_EQ(std::system(("sox " + dir + "/long.wav " + dir + "/long.flac").c_str()), 0);
  std::ofstream(dir + "/wav.scp") << "f flac -c -d -s " << dir << "/long.flac |\n"
                                  << "g cat " << dir << "/long.wav |\n";
  // SIGPIPE ignored, as under a Python parent: a command cut off then gets EPIPE and flac reports it
  // ("ERROR, decoded number of samples is smaller ..."), which the old header-only read caused.
  ASSERT_EQ(run("trap '' PIPE; " + kBin + "wav-to-duration scp:wav.scp ark,t:durations"), 0) << slurp(log);
  EXPECT_EQ(slurp(dir + "/durations"), "f 5 \ng 5 \n");
  EXPECT_EQ(slurp(log).find("ERROR"), std::string::npos) << slurp(log);
  // A command that fails after writing a complete header is an error, not a duration.
  std::ofstream(dir + "/bad.scp") << "h cat " << dir << "/long.wav; exit 3 |\n";
  EXPECT_EQ(run(kBin + "wav-to-duration scp:bad.scp ark,t:bad_durations"), 1);
  EXPECT_NE(slurp(log).find("exit status 3"), std::string::npos) << slurp(log);
}

}  // namespace
