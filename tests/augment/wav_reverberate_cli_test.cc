// The wav-reverberate program against golden outputs made by the test's own float64 model of
// Kaldi's documented semantics (reference_model.cc), and its command-line contract.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <utility>

#include "io/audio_io.h"
#include "reference_model.h"
#include "test_support.h"

namespace {

using reftest::Vec;
const std::string kBin = std::string(TSRIR_BIN_DIR) + "/wav-reverberate";

int run(const std::string& command) {
  int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class WavReverberateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(tsrir_test::make_scratch_dir("wavrvb").string());
    const double fs = 16000;
    x_ = new Vec(reftest::quantise16(reftest::speech_like(16000, fs, 21)));
    h_ = new Vec(reftest::synthetic_rir(4000, fs, 90, 0.5, 22));
    n1_ = new Vec(reftest::quantise16(reftest::noise_signal(9000, 23)));
    n2_ = new Vec(reftest::quantise16(reftest::noise_signal(30000, 24)));
    reftest::write_wav(d("speech.wav"), {*x_}, fs, 16);
    reftest::write_wav(d("rir16.wav"), {reftest::quantise16(*h_)}, fs, 16);
    reftest::write_wav(d("rir_float.wav"), {*h_}, fs, 32, true);
    reftest::write_wav(d("rir24.wav"), {*h_}, fs, 24);
    reftest::write_wav(d("noise1.wav"), {*n1_}, fs, 16);
    reftest::write_wav(d("noise2.wav"), {*n2_}, fs, 16);
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir_);
    delete dir_;
    delete x_;
    delete h_;
    delete n1_;
    delete n2_;
  }
  static std::string d(const std::string& name) { return *dir_ + "/" + name; }

  // Runs the program, reads its output and compares with the golden model output, written next
  // to it as golden_<tag>.wav (float) for inspection.
  void expect_golden(const std::string& options, const Vec& rir, const std::vector<reftest::Additive>& additive,
                     const reftest::Options& model, const std::string& tag, const std::string& rir_file = "") {
    reftest::Result want = reftest::wav_reverberate(*x_, 16000, rir, additive, model);
    reftest::write_wav(d("golden_" + tag + ".wav"), {want.output}, 16000, 32, true);
    const std::string out = d("out_" + tag + ".wav");
    std::string cmd = kBin + " --print-args=false " + options +
                      (rir_file.empty() ? "" : " --impulse-response=" + rir_file) + " " + d("speech.wav") + " " + out;
    ASSERT_EQ(run(cmd), 0) << cmd;
    tsrir::AudioInfo info;
    auto got = tsrir::read_audio_channels(out, &info);
    ASSERT_EQ(info.format.find("PCM_16") != std::string::npos || info.format.find("16") != std::string::npos, true)
        << info.format;
    ASSERT_EQ(got[0].size(), want.output.size()) << tag;
    // 16-bit output: rounding to the nearest step (0.5 LSB) plus float error; Kaldi's own
    // binary differs from this model by 1-4 LSB (its packed DC/Nyquist bins); we allow 1 LSB.
    double worst = 0;
    for (size_t i = 0; i < got[0].size(); ++i) {
      const double want_q = std::clamp(want.output[i], -1.0, 32767.0 / 32768.0);
      worst = std::max(worst, std::abs(got[0][i] - want_q) * 32768.0);
    }
    EXPECT_LE(worst, 1.0) << tag << ": max error in LSB";
  }

  static std::string* dir_;
  static Vec *x_, *h_, *n1_, *n2_;
};
std::string* WavReverberateCli::dir_ = nullptr;
Vec *WavReverberateCli::x_, *WavReverberateCli::h_, *WavReverberateCli::n1_, *WavReverberateCli::n2_;

TEST_F(WavReverberateCli, GoldenShiftNormalize) {
  Vec h16 = reftest::quantise16(*h_);
  reftest::Options o;
  expect_golden("", h16, {}, o, "default", d("rir16.wav"));
  o.shift_output = false;
  expect_golden("--shift-output=false", h16, {}, o, "noshift", d("rir16.wav"));
  o = {};
  o.normalize_output = false;
  expect_golden("--normalize-output=false", h16, {}, o, "nonorm", d("rir16.wav"));
}

TEST_F(WavReverberateCli, GoldenDurationAndVolume) {
  Vec h16 = reftest::quantise16(*h_);
  reftest::Options o;
  o.duration_s = 0.5;
  expect_golden("--duration=0.5", h16, {}, o, "dur_short", d("rir16.wav"));
  o.duration_s = 2.25;
  expect_golden("--duration=2.25", h16, {}, o, "dur_long", d("rir16.wav"));
  o = {};
  o.volume = 0.7;
  expect_golden("--volume=0.7", h16, {}, o, "volume", d("rir16.wav"));
}

TEST_F(WavReverberateCli, GoldenMultipleAdditiveSignals) {
  Vec h16 = reftest::quantise16(*h_);
  reftest::Options o;
  std::vector<reftest::Additive> add = {{*n1_, 5, 0.0, 0}, {*n2_, 10, 0.37, 0}};
  expect_golden("--additive-signals=" + d("noise1.wav") + "," + d("noise2.wav") + " --snrs=5,10 --start-times=0,0.37",
                h16, add, o, "additive", d("rir16.wav"));
  // No RIR: SNR relative to the input's power (Kaldi: early energy = input power).
  expect_golden("--additive-signals=" + d("noise2.wav") + " --snrs=0 --start-times=0.5", {}, {{*n2_, 0, 0.5, 0}}, o,
                "noise_only");
  // Kaldi's nested noise extension: "wav-reverberate --duration=T noise.wav - |" as an input.
  Vec tiled(16000);
  for (size_t i = 0; i < tiled.size(); ++i) tiled[i] = (*n1_)[i % n1_->size()];
  // Normalisation of the tiled noise is a no-op up to the power ratio of whole periods; model it.
  reftest::Options noise_model;
  noise_model.duration_s = 1.0;
  Vec nested = reftest::quantise16(reftest::wav_reverberate(*n1_, 16000, {}, {}, noise_model).output);
  expect_golden("'--additive-signals=" + kBin + " --print-args=false --duration=1 " + d("noise1.wav") +
                    " - |' --snrs=3 --start-times=0",
                h16, {{nested, 3, 0, 0}}, o, "nested", d("rir16.wav"));
}

TEST_F(WavReverberateCli, GoldenExtensions) {
  reftest::Options o;
  o.loop = true;
  expect_golden("--additive-signals=" + d("noise1.wav") +
                    " --snrs=1.5 --start-times=0 --additive-offsets=0.2 --loop-additive-signals=true",
                reftest::quantise16(*h_), {{*n1_, 1.5, 0, 0.2}}, o, "loop", d("rir16.wav"));
  o.full_reference = true;
  expect_golden("--additive-signals=" + d("noise1.wav") +
                    " --snrs=1.5 --start-times=0 --additive-offsets=0.2 --loop-additive-signals --snr-reference=full",
                reftest::quantise16(*h_), {{*n1_, 1.5, 0, 0.2}}, o, "loop_full", d("rir16.wav"));
}

// Kaldi reads only 16-bit PCM; TS-RIR writes float RIRs. Both float and 24-bit must work.
TEST_F(WavReverberateCli, FloatAnd24BitRirs) {
  reftest::Options o;
  expect_golden("", *h_, {}, o, "rir_float", d("rir_float.wav"));
  Vec h24(h_->size());
  for (size_t i = 0; i < h24.size(); ++i) h24[i] = std::round((*h_)[i] * 8388608.0) / 8388608.0;
  expect_golden("", h24, {}, o, "rir24", d("rir24.wav"));
}

TEST_F(WavReverberateCli, PipesAndStdio) {
  const std::string out = d("piped.wav");
  std::string cmd = "cat " + d("speech.wav") + " | " + kBin + " --print-args=false '--impulse-response=cat " +
                    d("rir16.wav") + " |' - - > " + out;
  ASSERT_EQ(run(cmd), 0);
  ASSERT_EQ(run(kBin + " --print-args=false --impulse-response=" + d("rir16.wav") + " " + d("speech.wav") + " " +
                d("direct.wav")),
            0);
  auto a = tsrir::read_audio(out), b = tsrir::read_audio(d("direct.wav"));
  EXPECT_EQ(a.samples, b.samples);
  ASSERT_EQ(run(kBin + " --print-args=false " + d("speech.wav") + " '| cat > " + d("outpipe.wav") + "'"), 0);
  EXPECT_EQ(tsrir::read_audio(d("outpipe.wav")).samples.size(), x_->size());
}

TEST_F(WavReverberateCli, NoiseAtAnotherRateIsResampled) {
  // The same noise at 8 kHz must give the output of the noise resampled to 16 kHz beforehand.
  Vec n8 = reftest::quantise16(reftest::noise_signal(8000, 31));
  reftest::write_wav(d("noise8k.wav"), {n8}, 8000, 16);
  std::vector<float> n8f(n8.begin(), n8.end());
  std::vector<float> n16 = tsrir::resample(n8f, 8000, 16000);
  reftest::write_wav(d("noise8k_as16k.wav"), {Vec(n16.begin(), n16.end())}, 16000, 32, true);
  for (const char* name : {"noise8k.wav", "noise8k_as16k.wav"}) {
    ASSERT_EQ(run(kBin + " --print-args=false --additive-signals=" + d(name) + " --snrs=2 --start-times=0 " +
                  d("speech.wav") + " " + d(std::string("o_") + name)),
              0);
  }
  auto a = tsrir::read_audio(d("o_noise8k.wav")).samples, b = tsrir::read_audio(d("o_noise8k_as16k.wav")).samples;
  ASSERT_EQ(a.size(), b.size());
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(double(a[i]) - b[i]) * 32768.0);
  EXPECT_LE(worst, 1.0);
}

// wav.scp lines exactly as Kaldi's reverberate_data_dir.py writes them (docs/reference/kaldi-conventions.md),
// run through bash with our bin directory first on PATH, as compute-mfcc-feats would run them.
TEST_F(WavReverberateCli, KaldiScriptPipesRunUnchanged) {
  const std::string path = "PATH=" + std::string(TSRIR_BIN_DIR) + ":$PATH ";
  const std::string isotropic = "wav-reverberate --duration=1.0 " + d("noise1.wav") + " - |";
  const std::string foreground = "wav-reverberate --impulse-response=\"" + d("rir16.wav") + "\"  " + d("noise2.wav") + " - |";
  const std::string kaldi_line = "cat " + d("speech.wav") + " | wav-reverberate --shift-output=true --impulse-response=\"" +
                                 d("rir16.wav") + "\" --additive-signals='" + isotropic + "," + foreground +
                                 "' --start-times='0,0.31' --snrs='10.0,5.0' - - |";
  const std::string out = d("kaldi_line.wav");
  std::ofstream(d("kaldi_line.sh")) << kaldi_line.substr(0, kaldi_line.size() - 1) << "\n";  // drop the final |
  ASSERT_EQ(run("cd " + *dir_ + " && " + path + "bash kaldi_line.sh > " + out + " 2>/dev/null"), 0);
  // The same mixture from the model: both noises as wav-reverberate would make them.
  reftest::Options dur;
  dur.duration_s = 1.0;
  Vec iso = reftest::quantise16(reftest::wav_reverberate(*n1_, 16000, {}, {}, dur).output);
  Vec h16 = reftest::quantise16(*h_);
  Vec fg = reftest::quantise16(reftest::wav_reverberate(*n2_, 16000, h16, {}, {}).output);
  reftest::Result want = reftest::wav_reverberate(*x_, 16000, h16, {{iso, 10, 0, 0}, {fg, 5, 0.31, 0}}, {});
  auto got = tsrir::read_audio(out).samples;
  ASSERT_EQ(got.size(), want.output.size());
  double worst = 0;
  for (size_t i = 0; i < got.size(); ++i) worst = std::max(worst, std::abs(got[i] - want.output[i]) * 32768.0);
  EXPECT_LE(worst, 1.0);
}

std::string file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::vector<std::string> temporaries_in(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) found.push_back(e.path().string());
  return found;
}

// --max-in-memory-duration=0 sends every input through the streaming passes (the path of inputs
// over 5 minutes): the output must be the in-memory path's, byte for byte, for every option the
// program has. (Chunk and block boundaries inside the passes are covered by
// reverberate_stream_test.cc; here it is the program's plumbing: channels, pipes, stdio.)
TEST_F(WavReverberateCli, StreamingPathWritesTheSameBytes) {
  // Stereo RIR and noises for --multi-channel-output, a stereo input for --input-wave-channel.
  reftest::write_wav(d("rir_stereo.wav"), {reftest::quantise16(*h_), reftest::quantise16(reftest::synthetic_rir(4000, 16000, 150, 0.4, 25))}, 16000, 16);
  reftest::write_wav(d("noise_stereo.wav"), {*n1_, reftest::quantise16(reftest::noise_signal(9000, 26))}, 16000, 16);
  reftest::write_wav(d("speech_stereo.wav"), {reftest::quantise16(reftest::speech_like(16000, 16000, 27)), *x_}, 16000, 16);
  const std::string rir = " --impulse-response=" + d("rir16.wav");
  const std::string noises = " --additive-signals=" + d("noise1.wav") + "," + d("noise2.wav");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"plain", rir},
      {"noshift", rir + " --shift-output=false"},
      {"nonorm", rir + " --normalize-output=false"},
      {"volume", rir + " --volume=0.6"},
      {"shorter", rir + " --duration=0.4"},
      {"tiled", rir + " --duration=2.7"},
      {"tiled_noshift", rir + " --duration=2.7 --shift-output=false --normalize-output=false"},
      {"kaldi_noise", rir + noises + " --snrs=5,10 --start-times=0,0.37"},
      {"looped", rir + noises + " --snrs=5,10 --start-times=0.1,0.37 --additive-offsets=0.2,1.3 --loop-additive-signals"},
      {"full_ref", rir + noises + " --snrs=5,10 --start-times=0,0 --loop-additive-signals --snr-reference=full"},
      {"no_rir", noises + " --snrs=0,3 --start-times=0.5,0"},
      {"multichannel", " --impulse-response=" + d("rir_stereo.wav") + " --multi-channel-output=true --additive-signals=" +
                           d("noise_stereo.wav") + " --snrs=4 --start-times=0.2 --loop-additive-signals"},
      {"rir_channel", " --impulse-response=" + d("rir_stereo.wav") + " --rir-channel=1 --additive-signals=" +
                          d("noise_stereo.wav") + " --noise-channel=1 --snrs=4 --start-times=0.2"},
  };
  const std::string stream = " --max-in-memory-duration=0";
  for (const auto& [tag, options] : cases) {
    SCOPED_TRACE(tag);
    const std::string mem = d("mem_" + tag + ".wav"), str = d("str_" + tag + ".wav");
    const std::string speech = d(tag == "rir_channel" ? "speech_stereo.wav" : "speech.wav");
    const std::string input_channel = tag == "rir_channel" ? " --input-wave-channel=1" : "";
    ASSERT_EQ(run(kBin + " --print-args=false" + input_channel + options + " " + speech + " " + mem), 0);
    ASSERT_EQ(run(kBin + " --print-args=false" + input_channel + stream + options + " " + speech + " " + str +
                  " 2> " + d("str.log")),
              0);
    // The streaming path really ran.
    EXPECT_NE(file_bytes(d("str.log")).find("passes over the file"), std::string::npos) << file_bytes(d("str.log"));
    EXPECT_EQ(file_bytes(mem), file_bytes(str));
  }
  const std::string want = file_bytes(d("mem_looped.wav"));
  const std::string looped = stream + rir + noises + " --snrs=5,10 --start-times=0.1,0.37 --additive-offsets=0.2,1.3 --loop-additive-signals";
  // Non-seekable inputs (a pipe, stdin) are copied to a temporary file first; stdout and a pipe
  // as outputs get the header first (its sizes known after pass 1). Temporaries of stdout
  // outputs go to $TMPDIR: a private one here, which must be left empty.
  std::filesystem::create_directories(d("tmp"));
  const std::string env = "TMPDIR=" + d("tmp") + " ";
  ASSERT_EQ(run(env + kBin + " --print-args=false" + looped + " 'cat " + d("speech.wav") + " |' " + d("s_pipe.wav") + " 2>/dev/null"), 0);
  EXPECT_EQ(file_bytes(d("s_pipe.wav")), want);
  ASSERT_EQ(run("cat " + d("speech.wav") + " | " + env + kBin + " --print-args=false" + looped + " - - > " + d("s_stdio.wav") + " 2>/dev/null"), 0);
  EXPECT_EQ(file_bytes(d("s_stdio.wav")), want);
  ASSERT_EQ(run(env + kBin + " --print-args=false" + looped + " " + d("speech.wav") + " '| cat > " + d("s_outpipe.wav") + "' 2>/dev/null"), 0);
  EXPECT_EQ(file_bytes(d("s_outpipe.wav")), want);
  EXPECT_TRUE(std::filesystem::is_empty(d("tmp")));
  EXPECT_TRUE(temporaries_in(*dir_).empty());
}

TEST_F(WavReverberateCli, StreamingPathErrorsLeaveNothing) {
  const std::string stream = " --print-args=false --max-in-memory-duration=0 --impulse-response=" + d("rir16.wav");
  const std::string bytes = file_bytes(d("speech.wav"));
  std::ofstream(d("cut.wav"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);  // header claims twice that
  std::filesystem::create_directories(d("tmp_err"));
  const std::string env = "TMPDIR=" + d("tmp_err") + " ";
  EXPECT_EQ(run(env + kBin + stream + " " + d("cut.wav") + " " + d("e1.wav") + " 2> " + d("e1.log")), 1);
  EXPECT_NE(file_bytes(d("e1.log")).find("cut.wav"), std::string::npos) << file_bytes(d("e1.log"));
  EXPECT_EQ(run(env + kBin + stream + " 'cat " + d("cut.wav") + " |' " + d("e2.wav") + " 2>/dev/null"), 1);
  EXPECT_EQ(run(env + kBin + stream + " 'cat " + d("speech.wav") + "; exit 3 |' " + d("e3.wav") + " 2> " + d("e3.log")), 1);
  EXPECT_NE(file_bytes(d("e3.log")).find("exit status 3"), std::string::npos) << file_bytes(d("e3.log"));
  EXPECT_EQ(run(env + kBin + stream + " --input-wave-channel=2 " + d("speech.wav") + " " + d("e4.wav") + " 2>/dev/null"), 1);
  for (const char* name : {"e1.wav", "e2.wav", "e3.wav", "e4.wav"}) EXPECT_FALSE(std::filesystem::exists(d(name))) << name;
  EXPECT_TRUE(std::filesystem::is_empty(d("tmp_err")));
  EXPECT_TRUE(temporaries_in(*dir_).empty());
}

// A microphone array's RIR with noises (issue 33), Kaldi's --multi-channel-output rule: output
// channel c = the speech through RIR channel c plus channel c of every additive signal, each scaled
// to its SNR against channel c's own early reverberant speech, then normalised per channel. The
// nested-noise extension keeps the array: a point-source noise (mono) through each channel of its
// 3-channel RIR, an isotropic 3-channel noise extended channel by channel. Each channel against the
// test's float64 model (nested step, 16-bit pipe rounding, then the outer step) within 1 LSB; the
// split form (--rir-channel=c --noise-channel=c) gives channel c exactly; a mono background noise
// or a 2-channel noise RIR with a 3-channel RIR is refused (exit 1) with a message.
TEST_F(WavReverberateCli, ArrayNoisesPerChannel) {
  const double fs = 16000;
  std::vector<Vec> rir(3), noise_rir(3), iso(3);
  for (int c = 0; c < 3; ++c) {
    rir[c] = reftest::synthetic_rir(3000, fs, 60 + 7 * c, 0.4, 40 + c);
    noise_rir[c] = reftest::synthetic_rir(2500, fs, 30 + 11 * c, 0.3, 50 + c);
    iso[c] = reftest::quantise16(reftest::noise_signal(12000, 60 + c, 0.2));
  }
  reftest::write_wav(d("array3.wav"), rir, fs, 32, true);
  reftest::write_wav(d("noise_rir3.wav"), noise_rir, fs, 32, true);
  reftest::write_wav(d("noise_rir2.wav"), {noise_rir[0], noise_rir[1]}, fs, 32, true);
  reftest::write_wav(d("iso3.wav"), iso, fs, 16);
  const std::string noises = " --additive-signals=" + d("iso3.wav") + "," + d("noise1.wav") + "," + d("iso3.wav") +
                             " --snrs=10,5,15 --start-times=0,0.2,0.1 --additive-impulse-responses=," +
                             d("noise_rir3.wav") + ", --additive-durations=1,0,0 --impulse-response=" + d("array3.wav");
  const std::string multi = d("multi.wav");
  ASSERT_EQ(run(kBin + " --print-args=false --multi-channel-output=true" + noises + " " + d("speech.wav") + " " + multi), 0);
  tsrir::AudioInfo info;
  const auto got = tsrir::read_audio_channels(multi, &info);
  ASSERT_EQ(got.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::to_string(c));
    reftest::Options extend;
    extend.duration_s = 1.0;
    // The nested steps as the pipes' `wav-reverberate --duration=1 iso3 -` and
    // `wav-reverberate --impulse-response=<noise RIR channel c> noise1 -` make them (16-bit).
    const Vec iso_extended = reftest::quantise16(reftest::wav_reverberate(iso[c], fs, {}, {}, extend).output);
    const Vec point_source = reftest::quantise16(reftest::wav_reverberate(*n1_, fs, noise_rir[c], {}, {}).output);
    std::vector<reftest::Additive> additive(3);
    additive[0].samples = iso_extended;
    additive[0].snr_db = 10;
    additive[1].samples = point_source;
    additive[1].snr_db = 5;
    additive[1].start_s = 0.2;
    additive[2].samples = iso[c];
    additive[2].snr_db = 15;
    additive[2].start_s = 0.1;
    const Vec want = reftest::wav_reverberate(*x_, fs, rir[c], additive, {}).output;
    ASSERT_EQ(got[c].size(), want.size());
    double worst = 0;
    for (size_t i = 0; i < want.size(); ++i)
      worst = std::max(worst, std::abs(got[c][i] - std::clamp(want[i], -1.0, 32767.0 / 32768.0)) * 32768.0);
    EXPECT_LE(worst, 1.0) << "max error in LSB";
    const std::string split = d("split" + std::to_string(c) + ".wav");
    const std::string pick = " --rir-channel=" + std::to_string(c) + " --noise-channel=" + std::to_string(c);
    ASSERT_EQ(run(kBin + " --print-args=false" + pick + noises + " " + d("speech.wav") + " " + split), 0);
    EXPECT_EQ(tsrir::read_audio_channels(split, &info).at(0), got[c]);
  }
  // Refused: a mono background noise for a 3-channel RIR (Kaldi asserts equal channel counts),
  // and a point-source noise whose RIR is not the same array's.
  const std::string log = d("array_err.log");
  auto refused = [&](const std::string& options, const std::string& expected) {
    EXPECT_EQ(run(kBin + " --print-args=false --multi-channel-output=true --impulse-response=" + d("array3.wav") +
                  options + " " + d("speech.wav") + " " + d("refused.wav") + " 2> " + log), 1) << options;
    std::ifstream f(log);
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(expected), std::string::npos) << text;
    EXPECT_FALSE(std::filesystem::exists(d("refused.wav")));
  };
  refused(" --additive-signals=" + d("noise1.wav") + " --snrs=5 --start-times=0 --additive-durations=1",
          "additive signal 1 has 1 channels but the impulse response has 3");
  refused(" --additive-signals=" + d("noise1.wav") + " --snrs=5 --start-times=0 --additive-impulse-responses=" +
              d("noise_rir2.wav"), "additive signal 1 has 2 channels but the impulse response has 3");
}

TEST_F(WavReverberateCli, CommandLineContract) {
  const std::string q = " 2>/dev/null >/dev/null";
  const std::string io = " " + d("speech.wav") + " " + d("c.wav");
  EXPECT_EQ(run(kBin + " --help" + q), 0);
  EXPECT_EQ(run(kBin + io + " --volume=2" + q), 1);                          // options after positionals
  EXPECT_EQ(run(kBin + " " + d("speech.wav") + q), 1);                       // one positional
  EXPECT_EQ(run(kBin + " --impulse-response " + d("rir16.wav") + io + q), 1);  // --name value
  EXPECT_EQ(run(kBin + " --no-such-option=1" + io + q), 1);
  EXPECT_EQ(run(kBin + " --additive-signals=" + d("noise1.wav") + io + q), 1);  // needs --snrs, --start-times
  EXPECT_EQ(run(kBin + " --additive-signals=" + d("noise1.wav") + " --snrs=1,2 --start-times=0,0" + io + q), 1);
  EXPECT_EQ(run(kBin + " --impulse-response=" + d("missing.wav") + io + q), 1);
  EXPECT_EQ(run(kBin + " '--impulse-response=false |'" + io + q), 1);      // failing input pipe
  EXPECT_FALSE(std::filesystem::exists(d("c.wav")));
  EXPECT_EQ(run(kBin + " --print-args=false --Shift_Output=FALSE" + io + q), 0);
  // --help prints the usage with an example and the reason for the program's name.
  ASSERT_EQ(run(kBin + " --help > " + d("help.txt") + " 2>&1"), 0);
  std::ifstream f(d("help.txt"));
  std::string help((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(help.find("e.g."), std::string::npos);
  EXPECT_NE(help.find("reverberate_data_dir.py"), std::string::npos);
  EXPECT_NE(help.find("--additive-offsets"), std::string::npos);
}

}  // namespace
