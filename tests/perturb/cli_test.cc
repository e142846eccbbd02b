// rir-perturb as a program: the set comes out with its ids and room ids, the log reports what the
// control changed, bad input is an error naming the file and line (exit 1, nothing written), and on
// the measured R3VIVAL RIRs (skipped without ../shared/data) T60 x0.33 gives a third of the T60.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/audio_io.h"
#include "io/wav_writer.h"
#include "metrics/rir_metrics.h"
#include "test_support.h"

namespace tsrir {
namespace {

const std::string kProgram = tsrir_test::program_path("rir-perturb");

class RirPerturbCli : public tsrir_test::TempDirTest {
 protected:
  // n decaying-noise RIRs at 16 kHz (T60 0.4 s, direct at 5 ms) in a Kaldi rir_list with room ids.
  std::string make_list(int n) {
    std::ofstream list(path("rir_list"));
    std::mt19937 gen(11);
    std::normal_distribution<double> normal;
    for (int i = 0; i < n; ++i) {
      Signal s;
      s.sample_rate_hz = 16000;
      s.samples.assign(12000, 0.0f);
      s.samples[80] = 0.9f;
      for (size_t k = 96; k < s.size(); ++k) s.samples[k] = float(0.2 * normal(gen) * std::pow(10.0, -3.0 * (k - 80) / 16000.0 / 0.4));
      const std::string wav = path("r" + std::to_string(i) + ".wav");
      write_wav(wav, s);
      list << "--rir-id r" << i << " --room-id room" << i % 2 << ' ' << wav << '\n';
    }
    return path("rir_list");
  }
};

TEST_F(RirPerturbCli, WritesTheSetWithIdsAndRoomsAndLogsTheChange) {
  const std::string list = make_list(4);
  const auto r = tsrir_test::run_command(kProgram + " --t60-scale=0.5 --num-threads=2 " + list + " " + path("out"));
  ASSERT_EQ(r.status, 0) << r.err;
  // The log reports the set's mean T60 before and after, as rir-metrics measures them.
  const size_t at = r.err.find("mean T60 ");
  ASSERT_NE(at, std::string::npos) << r.err;
  double before = 0, after = 0;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at, "mean T60 %lf -> %lf s", &before, &after), 2) << r.err;
  EXPECT_NEAR(before, 0.4, 0.04);
  EXPECT_NEAR(after / before, 0.5, 0.05);
  const std::string out_list = read_text("out/rir_list");
  for (int i = 0; i < 4; ++i) {
    EXPECT_NE(out_list.find("--rir-id r" + std::to_string(i) + " --room-id room" + std::to_string(i % 2)), std::string::npos)
        << out_list;
    EXPECT_TRUE(std::filesystem::exists(path("out/r" + std::to_string(i) + ".wav")));
  }
  EXPECT_NE(read_text("out/rir.scp").find("r3 "), std::string::npos);
}

TEST_F(RirPerturbCli, HelpAndErrors) {
  auto r = tsrir_test::run_command(kProgram + " --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("Example"), std::string::npos);
  write_text("bad_list", "--rir-id a --room-id x " + path("missing.wav") + "\n");
  r = tsrir_test::run_command(kProgram + " --t60-scale=0.5 " + path("bad_list") + " " + path("out"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("bad_list:1"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("out/rir_list")));
  r = tsrir_test::run_command(kProgram + " --t60-scale=-1 " + make_list(1) + " " + path("out"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--t60-scale"), std::string::npos) << r.err;
}

TEST_F(RirPerturbCli, R3vivalT60ScaledToAThird) {
  const std::filesystem::path r3v = std::filesystem::path(TSRIR_SOURCE_DIR) / "../shared/data/rirs/r3vival";
  if (!std::filesystem::exists(r3v)) GTEST_SKIP() << r3v << " is absent (../shared/data): the measured-RIR check is skipped";
  std::ofstream scp(path("real.scp"));
  std::vector<std::string> ids;
  for (const auto& e : std::filesystem::directory_iterator(r3v)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("RLRVarAcLab_Absorptive_000_", 0) == 0 && name.size() > 8 && name.substr(name.size() - 8) == "_ch7.wav") {
      ids.push_back(name.substr(0, name.size() - 4));
      scp << ids.back() << ' ' << e.path().string() << '\n';
    }
  }
  scp.close();
  ASSERT_EQ(ids.size(), 34u);
  const auto r = tsrir_test::run_command(kProgram + " --t60-scale=0.33 --format=float --num-threads=2 " + path("real.scp") +
                                         " " + path("out"));
  ASSERT_EQ(r.status, 0) << r.err;
  double ratio_sum = 0;
  for (const std::string& id : ids) {
    const RirMetrics before = measure_rir(read_audio(r3v.string() + "/" + id + ".wav"));
    const RirMetrics after = measure_rir(read_audio(path("out/" + id + ".wav")));
    ratio_sum += after.t60_s / before.t60_s;
  }
  EXPECT_NEAR(ratio_sum / ids.size(), 0.33, 0.03);
}

}  // namespace
}  // namespace tsrir
