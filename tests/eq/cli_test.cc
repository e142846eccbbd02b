// rir-eq as a program: modes, outputs, determinism and the bad inputs (clear errors,
// non-zero exit, nothing half-written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "eq_test_util.h"
#include "io/audio_io.h"
#include "io/rir_set.h"

using namespace tsrir;

namespace {

const std::string kRirEq = std::string(TSRIR_BIN_DIR) + "/rir-eq";

class RirEqCli : public ::testing::Test {
 protected:
  // Runs rir-eq with `args`; returns the exit status, stderr+stdout in *output.
  int run(const std::string& args, std::string* output = nullptr) {
    const std::string log = dir_.path("out.log");
    const int status = std::system((kRirEq + " " + args + " >" + log + " 2>&1").c_str());
    if (output) *output = dir_.read("out.log");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  // `count` decaying-noise RIRs at `fs` in <dir>/<name>/, listed in <dir>/<name>.scp.
  std::string make_set(const std::string& name, int count, double fs, uint64_t seed, int silent_index = -1) {
    std::filesystem::create_directories(dir_.path(name));
    std::ofstream scp(dir_.path(name + ".scp"));
    for (int i = 0; i < count; ++i) {
      Signal s = eqtest::decaying_noise_rir(name + std::to_string(i), fs, static_cast<size_t>(0.5 * fs), 0.4,
                                            static_cast<size_t>(0.005 * fs), -2.0, seed * 1000 + i);
      if (i == silent_index) std::fill(s.samples.begin(), s.samples.end(), 0.0f);
      const std::string wav = dir_.path(name + "/" + s.id + ".wav");
      write_wav(wav, s);
      scp << s.id << ' ' << wav << '\n';
    }
    return dir_.path(name + ".scp");
  }
  tsrir_test::ScratchDir dir_;
};

}  // namespace

TEST_F(RirEqCli, HelpAndUsageErrors) {
  std::string out;
  for (const std::string mode : {"", "fit ", "apply ", "gains "}) {
    EXPECT_EQ(run(mode + "--help", &out), 0) << mode;
    EXPECT_NE(out.find("xample"), std::string::npos) << mode;
  }
  EXPECT_NE(run("fit --no-such-option a b", &out), 0);
  EXPECT_NE(out.find("ERROR"), std::string::npos);
  EXPECT_NE(run("apply only_two_args x", &out), 0);
  EXPECT_NE(run("in.scp out", &out), 0);  // one-shot needs --real
  EXPECT_NE(out.find("--real"), std::string::npos);
  EXPECT_NE(run("fit --model=indep --components=3 a b", &out), 0);
  EXPECT_NE(run("apply --taps=2048 m a b", &out), 0);
}

TEST_F(RirEqCli, FitApplyWritesACompleteSetDeterministically) {
  const std::string real = make_set("real", 20, 16000, 1);
  const std::string sim = make_set("sim", 6, 16000, 2);
  std::string out;
  ASSERT_EQ(run("fit " + real + " " + dir_.path("eq.model"), &out), 0) << out;
  ASSERT_EQ(run("apply --seed=4 " + dir_.path("eq.model") + " " + sim + " " + dir_.path("eq1"), &out), 0) << out;
  EXPECT_NE(out.find("achieved"), std::string::npos);
  ASSERT_EQ(run("apply --seed=4 --num-threads=2 " + dir_.path("eq.model") + " " + sim + " " + dir_.path("eq2"), &out), 0);
  const std::vector<RirRef> in = read_rir_refs(sim, nullptr), a = read_rir_refs(dir_.path("eq1/rir.scp"), nullptr),
                            b = read_rir_refs(dir_.path("eq2/rir_list"), nullptr);
  ASSERT_EQ(a.size(), in.size());
  ASSERT_EQ(b.size(), in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(a[i].id, in[i].id);  // same ids (both sorted: sim0..sim5)
    const Signal x = load_rir(in[i]), y = load_rir(a[i]), z = load_rir(b[i]);
    EXPECT_EQ(y.samples.size(), x.samples.size());
    EXPECT_EQ(y.sample_rate_hz, 16000);
    EXPECT_EQ(y.samples, z.samples);  // same seed, any thread count: identical
  }
  // The one-shot form gives the same result for the same seed and model options.
  ASSERT_EQ(run("--real=" + real + " --seed=4 --model-out=" + dir_.path("eq3.model") + " " + sim + " " + dir_.path("eq3"), &out),
            0)
      << out;
  EXPECT_TRUE(dir_.exists("eq3.model"));
  EXPECT_EQ(load_rir(read_rir_refs(dir_.path("eq3/rir.scp"), nullptr)[0]).samples, load_rir(a[0]).samples);
  // gains mode: one line per RIR after a comment line.
  ASSERT_EQ(run("gains " + dir_.path("eq1/rir.scp") + " " + dir_.path("gains.txt"), &out), 0) << out;
  const std::string table = dir_.read("gains.txt");
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 7);
  // A report with before / target / achieved per RIR.
  ASSERT_EQ(run("apply --report=" + dir_.path("report.txt") + " " + dir_.path("eq.model") + " " + sim + " " + dir_.path("eq4"), &out), 0);
  EXPECT_NE(dir_.read("report.txt").find("sim3 before"), std::string::npos);
}

TEST_F(RirEqCli, FewerRealRirsThanModelParameters) {
  const std::string real = make_set("few", 10, 16000, 3);
  std::string out;
  EXPECT_NE(run("fit " + real + " " + dir_.path("eq.model"), &out), 0);
  EXPECT_NE(out.find("10 < 14"), std::string::npos) << out;
  EXPECT_FALSE(dir_.exists("eq.model"));
  const std::string real30 = make_set("thirty", 30, 16000, 4);
  EXPECT_NE(run("fit --model=gmm --components=2 --covariance=full " + real30 + " " + dir_.path("eq.model"), &out), 0);
  EXPECT_NE(out.find("30 < 71"), std::string::npos) << out;
  EXPECT_FALSE(dir_.exists("eq.model"));
}

TEST_F(RirEqCli, SampleRates) {
  const std::string real16 = make_set("r16", 16, 16000, 5);
  const std::string real48 = make_set("r48", 16, 48000, 6);
  std::string out;
  // Mixed rates in one real set: resampled to --sample-rate (logged), or an error with 0.
  {
    std::ofstream mixed(dir_.path("mixed.scp"));
    mixed << dir_.read("r16.scp") << dir_.read("r48.scp");
  }
  ASSERT_EQ(run("fit " + dir_.path("mixed.scp") + " " + dir_.path("eq.model"), &out), 0) << out;
  EXPECT_NE(out.find("resampled 16 of 32 RIRs"), std::string::npos) << out;
  EXPECT_NE(run("fit --sample-rate=0 " + dir_.path("mixed.scp") + " " + dir_.path("bad.model"), &out), 0);
  EXPECT_NE(out.find("48000 Hz"), std::string::npos) << out;
  EXPECT_FALSE(dir_.exists("bad.model"));
  // Applying a 16 kHz model to 48 kHz RIRs: an error naming the fix, or resampled with --resample.
  EXPECT_NE(run("apply " + dir_.path("eq.model") + " " + real48 + " " + dir_.path("out48"), &out), 0);
  EXPECT_NE(out.find("--resample"), std::string::npos) << out;
  EXPECT_FALSE(dir_.exists("out48"));
  ASSERT_EQ(run("apply --resample " + dir_.path("eq.model") + " " + real48 + " " + dir_.path("out48"), &out), 0) << out;
  EXPECT_EQ(load_rir(read_rir_refs(dir_.path("out48/rir.scp"), nullptr)[0]).sample_rate_hz, 16000);
  // A rate whose Nyquist lies below 8 kHz is refused.
  const std::string real8 = make_set("r8", 16, 8000, 7);
  EXPECT_NE(run("fit --sample-rate=0 " + real8 + " " + dir_.path("eq8.model"), &out), 0);
  EXPECT_NE(out.find("too low"), std::string::npos) << out;
  EXPECT_NE(run("fit --sample-rate=8000 " + real8 + " " + dir_.path("eq8.model"), &out), 0);
}

TEST_F(RirEqCli, SilentRirsAndBadModelsLeaveNothingBehind) {
  const std::string real = make_set("real", 16, 16000, 8);
  std::string out;
  // A silent RIR in the real set.
  const std::string silent_real = make_set("sreal", 16, 16000, 9, 5);
  EXPECT_NE(run("fit " + silent_real + " " + dir_.path("eq.model"), &out), 0);
  EXPECT_NE(out.find("sreal5"), std::string::npos) << out;
  EXPECT_NE(out.find("silent"), std::string::npos) << out;
  EXPECT_FALSE(dir_.exists("eq.model"));
  ASSERT_EQ(run("fit " + real + " " + dir_.path("eq.model"), &out), 0) << out;
  // A silent RIR in the input set: error, and an existing output dir stays as it was.
  const std::string sim = make_set("sim", 4, 16000, 10);
  ASSERT_EQ(run("apply " + dir_.path("eq.model") + " " + sim + " " + dir_.path("out"), &out), 0) << out;
  const std::string before = dir_.read("out/rir.scp");
  const std::string silent_sim = make_set("ssim", 4, 16000, 11, 2);
  EXPECT_NE(run("apply " + dir_.path("eq.model") + " " + silent_sim + " " + dir_.path("out"), &out), 0);
  EXPECT_NE(out.find("ssim2"), std::string::npos) << out;
  EXPECT_EQ(dir_.read("out/rir.scp"), before);
  // Model files that do not parse: file:line in the message, no output.
  dir_.write("broken.model", dir_.read("eq.model").substr(0, dir_.read("eq.model").size() / 2));
  EXPECT_NE(run("apply " + dir_.path("broken.model") + " " + sim + " " + dir_.path("out2"), &out), 0);
  EXPECT_NE(out.find(dir_.path("broken.model") + ":"), std::string::npos) << out;
  EXPECT_FALSE(dir_.exists("out2"));
  dir_.write("garbage.model", "hello world\n");
  EXPECT_NE(run("apply " + dir_.path("garbage.model") + " " + sim + " " + dir_.path("out2"), &out), 0);
  EXPECT_NE(out.find("garbage.model:1:"), std::string::npos) << out;
  EXPECT_NE(run("apply " + dir_.path("missing.model") + " " + sim + " " + dir_.path("out2"), &out), 0);
  EXPECT_FALSE(dir_.exists("out2"));
  // No leftovers of temporaries anywhere.
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir_.path(""))) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

// A microphone array's RIRs in the real set: each channel is one more measurement of the room.
// `gains` lists every channel as "<id>-ch<c>" with the gains the same file's channel gets when it
// is given alone (a mono file written from it), and `fit` on the array set makes the model that
// the mono channel files make.
TEST_F(RirEqCli, ArrayRirsAreMeasuredPerChannel) {
  std::filesystem::create_directories(dir_.path("arr"));
  std::filesystem::create_directories(dir_.path("mono"));
  std::ofstream arr_scp(dir_.path("arr.scp")), mono_scp(dir_.path("mono.scp"));
  for (int i = 0; i < 8; ++i) {
    std::vector<std::vector<float>> channels;
    for (int c = 0; c < 2; ++c) {
      const Signal s = eqtest::decaying_noise_rir("a", 16000, 8000, 0.3 + 0.1 * c + 0.02 * i, 80 + 7 * c, -2.0 + c,
                                                  100 + 10 * i + c);
      const std::string id = "a" + std::to_string(i) + "-ch" + std::to_string(c);
      write_wav(dir_.path("mono/" + id + ".wav"), s);
      mono_scp << id << ' ' << dir_.path("mono/" + id + ".wav") << '\n';
      channels.push_back(s.samples);
    }
    const std::string wav = dir_.path("arr/a" + std::to_string(i) + ".wav");
    write_wav_channels(wav, channels, 16000);
    arr_scp << "a" << i << ' ' << wav << '\n';
  }
  arr_scp.close();
  mono_scp.close();
  std::string out;
  ASSERT_EQ(run("gains " + dir_.path("arr.scp") + " " + dir_.path("arr_gains.txt"), &out), 0) << out;
  EXPECT_NE(out.find("8 multichannel RIR(s): each channel measured as one RIR (16 in all)"), std::string::npos) << out;
  ASSERT_EQ(run("gains " + dir_.path("mono.scp") + " " + dir_.path("mono_gains.txt"), &out), 0) << out;
  EXPECT_EQ(dir_.read("arr_gains.txt"), dir_.read("mono_gains.txt"));
  ASSERT_EQ(run("fit " + dir_.path("arr.scp") + " " + dir_.path("arr.model"), &out), 0) << out;
  ASSERT_EQ(run("fit " + dir_.path("mono.scp") + " " + dir_.path("mono.model"), &out), 0) << out;
  EXPECT_EQ(dir_.read("arr.model"), dir_.read("mono.model"));
}
