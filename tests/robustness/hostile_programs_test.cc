// Hostile names and content through the programs themselves (each test skips when its program is
// not built): ids and paths with quotes, ';', '$()' and backticks in the pipes reverberate-data
// writes, in rir-simulate's outputs and in wav-reverberate's inputs; lying headers; 10^5-line
// lists whose one bad line is the last (the error must name it, quickly and in bounded memory).
// A canary file appears if any command hidden in a name is ever run.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <sstream>

#include "io/audio_io.h"
#include "io/kaldi_table.h"
#include "io/rir_set.h"
#include "robust_test_util.h"
#include "util/error.h"

namespace fs = std::filesystem;
using robust::make_wav;

namespace {

class HostilePrograms : public robust::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    // The canary lands in the working directory of whatever shell would run a hidden command;
    // the hostile names below create it by relative name, so run everything from dir_.
    old_cwd_ = fs::current_path();
    fs::current_path(dir_);
    // A directory whose name alone would run commands if it were ever pasted unquoted into bash.
    hostile_dir_ = (dir_ / "d ir;$(touch CANARY)'q'").string();
    fs::create_directories(hostile_dir_);
  }
  void TearDown() override {
    fs::current_path(old_cwd_);
    ScratchDirTest::TearDown();
  }
  void expect_no_canary() const { EXPECT_FALSE(fs::exists(dir_ / "CANARY")) << "a command hidden in a name was run"; }
  std::string need(const std::string& program) const { return robust::program_path(program); }
  std::string rir_path() const { return hostile_dir_ + "/r 1;$(touch CANARY).wav"; }
  void write_inputs() const {
    std::vector<int16_t> rir(4000, 0);
    rir[40] = 20000;
    for (size_t i = 41; i < rir.size(); ++i) rir[i] = static_cast<int16_t>(((i * 7919) % 2001) - 1000) / static_cast<int16_t>(1 + i / 400);
    write_bytes(rir_path(), make_wav({}, rir));
    write_bytes(hostile_dir_ + "/s`touch CANARY`.wav", make_wav({}, robust::test_tone(16000)));
    write_bytes(hostile_dir_ + "/n\"oise.wav", make_wav({}, robust::test_tone(8000, 1000)));
    write_bytes(path("rir.scp"), "r1 " + rir_path() + "\n");
    write_bytes(path("noise.scp"), "n1 " + hostile_dir_ + "/n\"oise.wav\n");
  }
  fs::path old_cwd_;
  std::string hostile_dir_;
};

// A Kaldi id may hold any non-whitespace byte: this one is a command in every shell syntax.
const std::string kHostileId = "spk1-u;$(touch${IFS}CANARY)`touch${IFS}CANARY`'\"1";

TEST_F(HostilePrograms, ReverberateDataPipesRunOnlyWhatTheUserWrote) {
  const std::string prog = need("reverberate-data");
  if (prog.empty()) GTEST_SKIP() << "reverberate-data not built";
  write_inputs();
  fs::create_directories(path("data"));
  write_bytes(path("data/wav.scp"), kHostileId + " " + hostile_dir_ + "/s`touch CANARY`.wav\n");
  write_bytes(path("data/utt2spk"), kHostileId + " spk1\n");
  write_bytes(path("data/spk2utt"), "spk1 " + kHostileId + "\n");
  auto r = robust::run_argv({prog, "--rir-set-parameters", path("rir.scp"), "--noise-set-parameters", path("noise.scp"),
                             "--random-seed=3", path("data"), path("out")});
  ASSERT_EQ(r.status, 0) << r.output;
  tsrir::Table wav = tsrir::read_table(path("out/wav.scp"));
  ASSERT_EQ(wav.entries.size(), 1u);
  EXPECT_EQ(wav.entries[0].key, kHostileId);
  // Running the generated pipe through bash, as Kaldi will: audio out, nothing else run.
  tsrir::Signal s = tsrir::read_audio(wav.entries[0].value);
  EXPECT_EQ(s.size(), 16000u);
  expect_no_canary();
  // --write-wavs names files after the ids: the hostile id must stay one inert file name.
  r = robust::run_argv({prog, "--rir-set-parameters", path("rir.scp"), "--random-seed=3", "--write-wavs=" + path("wavs"),
                        path("data"), path("out2")});
  ASSERT_EQ(r.status, 0) << r.output;
  wav = tsrir::read_table(path("out2/wav.scp"));
  ASSERT_EQ(wav.entries.size(), 1u);
  EXPECT_EQ(tsrir::read_audio(wav.entries[0].value).size(), 16000u);
  expect_no_canary();
}

TEST_F(HostilePrograms, IdsThatClimbOutOfTheOutputDirectoryAreRefused) {
  const std::string prog = need("reverberate-data");
  if (prog.empty()) GTEST_SKIP() << "reverberate-data not built";
  write_inputs();
  fs::create_directories(path("data"));
  const std::string id = "spk1-../../escaped";
  write_bytes(path("data/wav.scp"), id + " " + hostile_dir_ + "/s`touch CANARY`.wav\n");
  write_bytes(path("data/utt2spk"), id + " spk1\n");
  write_bytes(path("data/spk2utt"), "spk1 " + id + "\n");
  fs::create_directories(path("deep/er"));
  auto r = robust::run_argv({prog, "--rir-set-parameters", path("rir.scp"), "--random-seed=3",
                             "--write-wavs=" + path("deep/er/wavs"), path("data"), path("out")});
  // Either refused with the id named, or written inside the wav directory: never outside it.
  if (r.status != 0) {
    EXPECT_NE(r.output.find("escaped"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(path("escaped.wav")) || fs::exists(path("deep/escaped.wav")))
      << "an utterance id wrote a file outside --write-wavs";
}

TEST_F(HostilePrograms, RirSimulateWithHostileIdsWritesReadableLists) {
  const std::string prog = need("rir-simulate");
  if (prog.empty()) GTEST_SKIP() << "rir-simulate not built";
  write_bytes(path("rooms.txt"), "r;$(touch${IFS}CANARY)'1 room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.3\n");
  auto r = robust::run_argv({prog, path("rooms.txt"), hostile_dir_ + "/sim"});
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* list : {"rir.scp", "rir_list"}) {
    auto refs = tsrir::read_rir_refs(hostile_dir_ + "/sim/" + list);
    ASSERT_EQ(refs.size(), 1u) << list;
    EXPECT_EQ(refs[0].id, "r;$(touch${IFS}CANARY)'1");
    EXPECT_GT(tsrir::load_rir(refs[0]).size(), 1000u) << list;
  }
  expect_no_canary();
}

TEST_F(HostilePrograms, WavReverberateRejectsLyingHeadersWithoutOutput) {
  const std::string prog = need("wav-reverberate");
  if (prog.empty()) GTEST_SKIP() << "wav-reverberate not built";
  write_inputs();
  robust::WavSpec lie;
  lie.data_size = 64000;  // claims 2 s, holds 0.1 s
  write_bytes(path("short.wav"), make_wav(lie, robust::test_tone(1600)));
  auto r = robust::run_argv({prog, "--impulse-response=" + rir_path(), path("short.wav"), path("out.wav")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("short.wav"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out.wav")));
  // An RIR file that is text, through the Kaldi-style option.
  write_bytes(path("text.wav"), "not audio\n");
  r = robust::run_argv({prog, "--impulse-response=" + path("text.wav"), hostile_dir_ + "/s`touch CANARY`.wav", path("out.wav")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("text.wav"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out.wav")));
  expect_no_canary();
}

// 10^5-line lists whose only bad line is the last: every program reads the whole list before
// working, so the error names line 100001 at once (no RIR simulated or measured first).
TEST_F(HostilePrograms, HundredThousandLineListsFailAtTheirLastLine) {
  const int n = 100000;
  std::ostringstream rooms, scp;
  for (int i = 0; i < n; ++i) {
    rooms << "r" << i << " room=5,4,3 src=1,1,1 mic=3,2,1.5 t60=0.4\n";
    scp << "r" << i << " /nonexistent/r.wav\n";
  }
  rooms << "r5 room=5,4,3 src=1,1,1 mic=3,2,1.5 t60=0.4\n";
  scp << "r5 /nonexistent/r.wav\n";
  write_bytes(path("rooms.txt"), rooms.str());
  write_bytes(path("rir.scp"), scp.str());
  struct Case {
    std::string program;
    std::vector<std::string> args;
    std::string where;
  };
  const std::vector<Case> cases = {
      {"rir-simulate", {path("rooms.txt"), path("sim")}, "rooms.txt:100001"},
      {"rir-metrics", {path("rir.scp")}, "rir.scp:100001"},
      {"rir-eq", {"gains", path("rir.scp"), "-"}, "rir.scp:100001"},
  };
  for (const auto& c : cases) {
    const std::string prog = need(c.program);
    if (prog.empty()) continue;
    std::vector<std::string> argv = {prog};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    auto r = robust::run_argv(argv);
    EXPECT_EQ(r.status, 1) << c.program;
    EXPECT_NE(r.output.find(c.where), std::string::npos) << c.program << ": " << r.output.substr(0, 2000);
  }
  EXPECT_FALSE(fs::exists(path("sim")));
  // Peak memory of those children: a 10^5-line list is a few MB of text.
  EXPECT_LT(robust::children_peak_rss_mb(), 1024.0);
}

}  // namespace
