// rir-diagnose as a program: outputs, options and bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "diagnose/effect.h"
#include "hidden_effects.h"
#include "io/audio_io.h"
#include "sim/room_list.h"
#include "test_support.h"

namespace tsrir {
namespace {

const std::string kBin = std::string(TSRIR_BIN_DIR) + "/rir-diagnose";

int run(const std::string& command, std::string* output = nullptr) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  const int status = pclose(pipe);
  if (output) *output = out;
  return WEXITSTATUS(status);
}

class DiagnoseCli : public tsrir_test::TempDirTest {
 protected:
  // A small hidden-offset set written as files: room list + scp of float WAVs.
  void write_set(size_t count) {
    const auto rooms = testdata::make_test_rooms(count, 41);
    const auto set = testdata::make_hidden_set(rooms, {"time_offset"}, 41);
    std::string list, scp;
    for (size_t i = 0; i < rooms.size(); ++i) {
      list += sim::format_room_list_line(rooms[i]) + "\n";
      const std::string wav = path(rooms[i].rir_id + ".wav");
      AudioWriteOptions o;
      o.format = SampleFormat::kFloat32;
      write_wav(wav, set.measured[i], o);
      scp += rooms[i].rir_id + " " + wav + "\n";
    }
    write_text("rooms.txt", list);
    write_text("rir.scp", scp);
  }
};

TEST_F(DiagnoseCli, WritesFindingsReportAndModels) {
  write_set(12);
  std::string out;
  ASSERT_EQ(run(kBin + " --num-threads=2 " + path("rooms.txt") + " " + path("rir.scp") + " " + path("out"), &out), 0) << out;
  const std::string json = read_text("out/findings.json");
  for (const auto& effect : diagnose::effect_registry().effects()) {
    EXPECT_NE(json.find("\"effect\": \"" + effect->name() + "\""), std::string::npos) << effect->name();
    // Its thresholds, by name and value.
    for (const diagnose::Threshold& t : effect->thresholds()) {
      EXPECT_NE(json.find("\"" + t.name + "\": "), std::string::npos) << effect->name() << "." << t.name;
    }
  }
  EXPECT_NE(json.find("\"gain\""), std::string::npos);
  EXPECT_NE(json.find("\"fit_ids\""), std::string::npos);
  EXPECT_NE(json.find("onset_shift:latency_ms="), std::string::npos);
  const std::string html = read_text("out/report.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);  // self-contained, no scripts
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_NE(read_text("out/extended_models").find("gas+onset_shift"), std::string::npos);
  EXPECT_NE(out.find("DETECTED time_offset"), std::string::npos) << out;
}

// Options from a Kaldi-style config file, the command line overriding it; the same outputs as the
// options given on the command line.
TEST_F(DiagnoseCli, ConfigFile) {
  write_set(12);
  write_text("diag.conf", "# rir-diagnose settings\n--sample-rate=16000\n--seed=5\n--num-threads=1\n");
  std::string out_config, out_cli;
  ASSERT_EQ(run(kBin + " --config=" + path("diag.conf") + " --num-threads=2 " + path("rooms.txt") + " " + path("rir.scp") +
                    " " + path("out_config"),
                &out_config),
            0)
      << out_config;
  ASSERT_EQ(run(kBin + " --fs=16000 --random-seed=5 --num-threads=2 " + path("rooms.txt") + " " + path("rir.scp") + " " +
                    path("out_cli"),
                &out_cli),
            0)
      << out_cli;
  EXPECT_EQ(read_text("out_config/extended_models"), read_text("out_cli/extended_models"));
  // --seed reached the diagnosis: another seed gives other simulations (and fitted values).
  std::string out_seed1;
  ASSERT_EQ(run(kBin + " --seed=1 " + path("rooms.txt") + " " + path("rir.scp") + " " + path("out_seed1"), &out_seed1), 0);
  EXPECT_NE(read_text("out_seed1/findings.json"), read_text("out_cli/findings.json"));
  write_text("bad.conf", "--sample-rate=16000\n--no-such-option=1\n");
  EXPECT_NE(run(kBin + " --config=" + path("bad.conf") + " a b c", &out_cli), 0);
  EXPECT_NE(out_cli.find("bad.conf:2"), std::string::npos) << out_cli;
}

TEST_F(DiagnoseCli, HelpAndBadInput) {
  std::string out;
  EXPECT_EQ(run(kBin + " --help", &out), 0);
  EXPECT_NE(out.find("Example"), std::string::npos);
  // The catalog with every threshold and why it has its value.
  for (const auto& effect : diagnose::effect_registry().effects()) {
    EXPECT_NE(out.find("  " + effect->name() + "\n"), std::string::npos) << effect->name();
    for (const diagnose::Threshold& t : effect->thresholds()) {
      EXPECT_NE(out.find("- " + t.name + " = "), std::string::npos) << effect->name() << "." << t.name;
    }
  }
  EXPECT_NE(run(kBin + " --no-such-option a b c", &out), 0);

  write_set(8);
  // A measured id without a room-list line: error naming the scp line, no output directory.
  write_text("extra.scp", read_text("rir.scp") + "ghost " + path("pos100.wav") + "\n");
  EXPECT_NE(run(kBin + " " + path("rooms.txt") + " " + path("extra.scp") + " " + path("out2"), &out), 0);
  EXPECT_NE(out.find("extra.scp:9"), std::string::npos) << out;
  EXPECT_NE(out.find("ghost"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(path("out2")));
  // A malformed room list line.
  write_text("bad_rooms.txt", read_text("rooms.txt") + "pos999 room=6,4,3 src=1,1,1\n");
  EXPECT_NE(run(kBin + " " + path("bad_rooms.txt") + " " + path("rir.scp") + " " + path("out3"), &out), 0);
  EXPECT_NE(out.find("bad_rooms.txt:9"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(path("out3")));
  // Too few RIRs for a decision over a set.
  std::ifstream in(path("rir.scp"));
  std::string line, few;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) few += line + "\n";
  write_text("few.scp", few);
  EXPECT_NE(run(kBin + " " + path("rooms.txt") + " " + path("few.scp") + " " + path("out4"), &out), 0);
  EXPECT_NE(out.find("at least 6"), std::string::npos) << out;
}

}  // namespace
}  // namespace tsrir
