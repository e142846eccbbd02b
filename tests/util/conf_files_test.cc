// Every top-level conf/*.conf is read by its program's --config without an error: the file's
// options exist and their values parse. A program given only --config stops at its arguments
// ("wrong number of arguments"), which it checks after reading the config file, so reaching that
// error proves the file was accepted. A new conf file must be added to the table below.
#include <dirent.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <map>
#include <string>

#include "test_support.h"

namespace {

const std::string kBin = TSRIR_BIN_DIR;
const std::string kConf = std::string(TSRIR_SOURCE_DIR) + "/conf";

// conf file -> the command that reads it (the recipe's use).
const std::map<std::string, std::string> kReaders = {
    {"rir-simulate.conf", "rir-simulate"},      {"rir-eq.conf", "rir-eq fit"},
    {"rir-eq-apply.conf", "rir-eq apply"},      {"rir-metrics.conf", "rir-metrics"},
    {"reverberate.conf", "reverberate-data"},   {"asr-train-proxy.conf", "asr-train"},
};

using tsrir_test::slurp;

struct Result {
  int status;
  std::string err;
};

Result run(const std::string& command) {
  const tsrir_test::CommandResult r = tsrir_test::run_command(command);
  return {r.status, r.err};
}

std::string reader_of(const std::string& file) {
  auto it = kReaders.find(file);
  if (it != kReaders.end()) return it->second;
  if (file.rfind("ts-rirgan", 0) == 0) return "ts-rirgan-train";  // conf/ts-rirgan*.conf
  return "";
}

}  // namespace

TEST(ConfFiles, EveryConfFileParsesWithItsProgram) {
  DIR* dir = opendir(kConf.c_str());
  ASSERT_NE(dir, nullptr) << kConf;
  int checked = 0;
  while (dirent* e = readdir(dir)) {
    const std::string file = e->d_name;
    if (file.size() < 6 || file.compare(file.size() - 5, 5, ".conf") != 0) continue;
    const std::string reader = reader_of(file);
    EXPECT_FALSE(reader.empty()) << "conf/" << file << ": which program reads it? Add it to kReaders.";
    if (reader.empty()) continue;
    const std::string program = reader.substr(0, reader.find(' '));
    if (access((kBin + "/" + program).c_str(), X_OK) != 0) {
      // ts-rirgan-train and asr-train exist only in builds with LibTorch.
      EXPECT_TRUE(program == "ts-rirgan-train" || program == "asr-train") << program << " is not built";
      continue;
    }
    const Result r = run(kBin + "/" + reader + " --config=" + kConf + "/" + file);
    EXPECT_EQ(r.status, 1) << file << ": " << r.err;
    EXPECT_NE(r.err.find("wrong number of arguments"), std::string::npos) << file << ": " << r.err;
    ++checked;
  }
  closedir(dir);
  EXPECT_GE(checked, 5);
}

TEST(ConfFiles, AMisspelledOptionInAConfFileIsCaught) {
  // The check above can fail: a conf file with an unknown option does not reach the arguments.
  tsrir_test::ScratchDir scratch;
  const std::string path = scratch.write("typo.conf", "# a typo\n--definiton=irstats\n");
  const Result r = run(kBin + "/rir-metrics --config=" + path);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(path + ":2: unknown option '--definiton'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("wrong number of arguments"), std::string::npos) << r.err;
}

TEST(ConfFiles, AliasesAndAConfigFileGiveTheSameRirsAsTheOptions) {
  tsrir_test::ScratchDir scratch;
  const std::string dir = scratch.dir().string();
  scratch.write("rooms.txt", "r1 room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.4\n");
  scratch.write("sim.conf", "# as the options of run a\n--sample-rate=8000\n--seed=-5\n--length=0.25\n--format=float\n");
  const std::string sim = kBin + "/rir-simulate ";
  const std::string rooms = " " + dir + "/rooms.txt ";
  ASSERT_EQ(run(sim + "--sample-rate=8000 --seed=-5 --length=0.25 --format=float" + rooms + dir + "/a").status, 0);
  ASSERT_EQ(run(sim + "--fs=8000 --random-seed=-5 --length=0.25 --format=float" + rooms + dir + "/b").status, 0);
  ASSERT_EQ(run(sim + "--config=" + dir + "/sim.conf" + rooms + dir + "/c").status, 0);
  ASSERT_EQ(run(sim + "--config=" + dir + "/sim.conf --seed=6" + rooms + dir + "/d").status, 0);
  const std::string a = slurp(dir + "/a/r1.wav");
  ASSERT_GT(a.size(), 2000u);
  EXPECT_EQ(a, slurp(dir + "/b/r1.wav"));
  EXPECT_EQ(a, slurp(dir + "/c/r1.wav"));
  EXPECT_NE(a, slurp(dir + "/d/r1.wav"));  // the command line overrides the file's seed
  EXPECT_EQ(slurp(dir + "/d/r1.wav").size(), a.size());
}
