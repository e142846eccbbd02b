// Data safety (issue 14): no program destroys what it did not write. Every test puts sentinel
// files (a user's own files) in and around the output locations, snapshots every input and every
// sentinel byte for byte, runs the programs as a careless user would (outputs over inputs, over
// unrelated directories, two runs sharing a directory, symlinked paths, Ctrl-C and SIGKILL
// mid-run), and then checks:
//  - every sentinel and every input is byte-identical (nothing deleted, nothing replaced);
//  - every data dir that validates (validate-data-dir exit 0) points only at files that exist;
//  - refusals are errors naming the directory and the way out (--overwrite), and leave nothing new.
// The first three tests are the data-loss cases of the issue, reproduced as reported.
// Programs not built in this build (the GAN programs without LibTorch) are skipped by name.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include "robust_test_util.h"

namespace fs = std::filesystem;
using robust::make_wav;

namespace {

using Tree = std::map<std::string, std::string>;  // path relative to the scratch dir -> bytes

class DataSafety : public robust::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    old_cwd_ = fs::current_path();
    fs::current_path(dir_);  // the programs get relative paths, as a user types them
  }
  void TearDown() override {
    fs::current_path(old_cwd_);
    ScratchDirTest::TearDown();
  }

  std::string need(const std::string& program) const { return robust::program_path(program); }

  // eq.model from rirs/rir.scp, for the cases that apply it (none when rir-eq is not built).
  void fit_eq_model_if_built() {
    if (!need("rir-eq").empty()) {
      ASSERT_EQ(run({need("rir-eq"), "fit", "rirs/rir.scp", "eq.model"}).status, 0);
    }
  }

  // Every file under `rel` (or the file itself), bytes included.
  Tree tree(const std::string& rel) const {
    Tree t;
    const fs::path p = dir_ / rel;
    if (fs::is_regular_file(p)) {
      t[rel] = read_bytes(p.string());
    } else if (fs::is_directory(p)) {
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file()) t[fs::relative(e.path(), dir_).string()] = read_bytes(e.path().string());
    }
    return t;
  }
  Tree trees(const std::vector<std::string>& rels) const {
    Tree all;
    for (const auto& r : rels) {
      Tree t = tree(r);
      all.insert(t.begin(), t.end());
    }
    return all;
  }
  void expect_unchanged(const Tree& before) const {
    for (const auto& [rel, bytes] : before) {
      ASSERT_TRUE(fs::exists(dir_ / rel)) << rel << " was deleted";
      EXPECT_TRUE(read_bytes(path(rel)) == bytes) << rel << " was changed";
    }
  }
  void sentinel(const std::string& rel) const {
    fs::create_directories((dir_ / rel).parent_path());
    write_bytes(path(rel), "a user's own file: " + rel + "\n");
  }

  // `n` RIRs in `rel`/ with rir.scp and rir_list (rooms of two RIRs each).
  void make_rirs(const std::string& rel, int n, unsigned seed = 1, size_t length = 4000) const {
    fs::create_directories(dir_ / rel);
    std::mt19937 rng(seed);
    std::string scp, list;
    for (int i = 0; i < n; ++i) {
      const std::string id = "r" + std::to_string(i);
      const std::string wav = rel + "/" + id + ".wav";
      write_bytes(path(wav), make_wav({}, robust::synthetic_rir(rng, 0.25 + 0.05 * (i % 5), length)));
      scp += id + " " + wav + "\n";
      list += "--rir-id " + id + " --room-id room" + std::to_string(i / 2) + " " + wav + "\n";
    }
    write_bytes(path(rel + "/rir.scp"), scp);
    write_bytes(path(rel + "/rir_list"), list);
  }
  // A Kaldi data dir `rel` of `n` utterances whose audio lives in `audio_rel`.
  void make_data(const std::string& rel, const std::string& audio_rel, int n, const std::string& spk = "spk1",
                 double seconds = 0.5) const {
    fs::create_directories(dir_ / rel);
    fs::create_directories(dir_ / audio_rel);
    std::string wav, u2s, s2u = spk;
    for (int i = 0; i < n; ++i) {
      const std::string id = spk + "-u" + std::to_string(i);
      const std::string audio = audio_rel + "/" + id + ".wav";
      write_bytes(path(audio), make_wav({}, robust::test_tone(static_cast<size_t>(seconds * 16000), 300.0 + 20 * i)));
      wav += id + " " + audio + "\n";
      u2s += id + " " + spk + "\n";
      s2u += " " + id;
    }
    write_bytes(path(rel + "/wav.scp"), wav);
    write_bytes(path(rel + "/utt2spk"), u2s);
    write_bytes(path(rel + "/spk2utt"), s2u + "\n");
  }

  robust::RunResult run(const std::vector<std::string>& argv) const { return robust::run_argv(argv); }
  robust::RunResult rvb(const std::vector<std::string>& args) const {
    std::vector<std::string> a = {need("reverberate-data"), "--rir-set-parameters", "rirs/rir_list", "--random-seed=3"};
    a.insert(a.end(), args.begin(), args.end());
    return run(a);
  }
  void expect_refused(const robust::RunResult& r, const std::string& names) const {
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("ERROR"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(names), std::string::npos) << "the error does not name " << names << ":\n" << r.output;
  }

  // Every data dir under the scratch dir that validates points only at files that exist.
  void expect_valid_data_dirs_point_at_existing_files() const {
    const std::string validate = need("validate-data-dir");
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      if (!e.is_regular_file() || e.path().filename() != "wav.scp") continue;
      if (e.path().string().find(".tmp.") != std::string::npos) continue;
      const std::string data = e.path().parent_path().string();
      if (!validate.empty() && run({validate, data}).status != 0) continue;
      std::istringstream in(read_bytes(e.path().string()));
      for (std::string line; std::getline(in, line);) {
        const std::string value = line.substr(line.find(' ') + 1);
        if (!value.empty() && value.back() == '|') continue;  // a pipe: checked by the pipe tests
        EXPECT_TRUE(fs::exists(value) || fs::exists(fs::path(data).parent_path() / value) || fs::exists(dir_ / value))
            << data << " validates but points at " << value << ", which does not exist";
      }
    }
  }

  fs::path old_cwd_;
};

// Issue case 1: --write-wavs audio data/in data/out, where data/in/wav.scp points at audio/*.wav,
// deleted the clean input audio.
TEST_F(DataSafety, WriteWavsIntoTheInputAudioDirIsRefused) {
  if (need("reverberate-data").empty()) GTEST_SKIP() << "reverberate-data not built";
  make_rirs("rirs", 4);
  make_data("data/in", "audio", 3);
  const Tree before = trees({"audio", "data", "rirs"});
  expect_refused(rvb({"--write-wavs", "audio", "data/in", "data/out"}), "audio");
  expect_unchanged(before);
  EXPECT_FALSE(fs::exists(path("data/out"))) << "a refused run left its output directory";
  // The same through a symlink to the audio directory.
  fs::create_directory_symlink(path("audio"), path("link"));
  expect_refused(rvb({"--write-wavs", "link", "data/in", "data/out"}), "audio");
  // Through --overwrite too: an input is never an output.
  expect_refused(rvb({"--overwrite", "--write-wavs", "audio", "data/in", "data/out"}), "audio");
  expect_unchanged(before);
}

// Issue case 2: --write-wavs data data/clean out/rvb deleted the input data dir and data/README.
TEST_F(DataSafety, WriteWavsIntoADirHoldingTheInputDataDirIsRefused) {
  if (need("reverberate-data").empty()) GTEST_SKIP() << "reverberate-data not built";
  make_rirs("rirs", 4);
  make_data("data/clean", "corpus", 3);
  sentinel("data/README");
  const Tree before = trees({"data", "corpus", "rirs"});
  expect_refused(rvb({"--write-wavs", "data", "data/clean", "out/rvb"}), "data");
  expect_unchanged(before);
  EXPECT_FALSE(fs::exists(path("out"))) << "a refused run left an empty parent directory";
  // An output data dir inside the input data dir, and the input itself, are refused as well.
  expect_refused(rvb({"data/clean", "data/clean/rvb"}), "data/clean");
  expect_refused(rvb({"data/clean", "data"}), "data");
  expect_unchanged(before);
}

// Issue case 3: two sets written with the same --write-wavs exp/shared; the second deleted the
// first set's wavs, and the first data dir still validated.
TEST_F(DataSafety, TwoSetsSharingAWavDirKeepEachOthersWavs) {
  if (need("reverberate-data").empty()) GTEST_SKIP() << "reverberate-data not built";
  make_rirs("rirs", 4);
  make_data("data/a", "audio_a", 3, "spkA");
  make_data("data/b", "audio_b", 2, "spkB");
  sentinel("exp/shared/NOTES");
  fs::create_directories(path("exp/shared"));
  // A directory the toolkit does not own is refused until the user says so.
  expect_refused(rvb({"--write-wavs", "exp/shared", "data/a", "exp/a"}), "--overwrite");
  EXPECT_FALSE(fs::exists(path("exp/a")));
  ASSERT_EQ(rvb({"--overwrite", "--write-wavs", "exp/shared", "data/a", "exp/a"}).status, 0);
  const Tree first = trees({"exp/a/wav.scp", "exp/shared/spkA-u0.wav", "exp/shared/spkA-u1.wav", "exp/shared/spkA-u2.wav",
                            "exp/shared/NOTES"});
  ASSERT_EQ(first.size(), 5u);
  // The second set has other ids: both sets live side by side.
  auto r = rvb({"--write-wavs", "exp/shared", "data/b", "exp/b"});
  ASSERT_EQ(r.status, 0) << r.output;
  expect_unchanged(first);
  EXPECT_TRUE(fs::exists(path("exp/shared/spkB-u1.wav")));
  // A second set with the same ids (same input, another data dir) would replace the first set's
  // wavs under exp/a's feet: refused, the first set intact.
  expect_refused(rvb({"--write-wavs", "exp/shared", "data/a", "exp/a2"}), "exp/a");
  expect_unchanged(first);
  EXPECT_FALSE(fs::exists(path("exp/a2")));
  // Re-running the first command replaces its own wavs only.
  ASSERT_EQ(rvb({"--write-wavs", "exp/shared", "data/a", "exp/a"}).status, 0);
  expect_unchanged(first);
  EXPECT_TRUE(fs::exists(path("exp/shared/spkB-u0.wav")));
  expect_valid_data_dirs_point_at_existing_files();
}

// A sentinel in every output location of every program: refused without --overwrite; with it the
// program writes its own files beside the sentinel; a re-run (now owned) needs no --overwrite; and
// a user file under one of the program's own names is never replaced silently.
TEST_F(DataSafety, SentinelsInEveryOutputLocationSurvive) {
  make_rirs("rirs", 16);
  make_data("data/in", "audio", 2);
  write_bytes(path("rooms.txt"), "s1 room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.3\n"
                                 "s2 room=6,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.4\n");
  std::vector<std::string> ids, wavs;
  fs::create_directories(path("measured"));
  for (int i = 0; i < 8; ++i) {
    ids.push_back("m" + std::to_string(i));
    wavs.push_back(path("measured/m" + std::to_string(i) + ".wav"));
  }
  robust::write_diagnose_inputs(ids, wavs, path("diag_rooms.txt"), path("measured.scp"), 8000);
  struct Case {
    std::string program, out;
    std::vector<std::string> args;  // the output location last
    std::string own_name;           // a file name the program writes there
  };
  std::vector<Case> cases = {
      {"rir-simulate", "o_sim", {"rooms.txt", "o_sim"}, "rir.scp"},
      {"rir-eq", "o_eq", {"apply", "--seed=1", "eq.model", "rirs/rir.scp", "o_eq"}, "rir_list"},
      {"rir-diagnose", "o_diag", {"--num-threads=1", "diag_rooms.txt", "measured.scp", "o_diag"}, "findings.json"},
      {"reverberate-data", "o_data", {"--rir-set-parameters", "rirs/rir_list", "data/in", "o_data"}, "wav.scp"},
      {"reverberate-data", "o_wavs", {"--rir-set-parameters", "rirs/rir_list", "--write-wavs=o_wavs", "data/in", "o_d2"},
       "spk1-u0.wav"},
  };
  if (!need("ts-rirgan-train").empty()) {
    cases.push_back({"ts-rirgan-train", "o_gan",
                     {"--real=rirs/rir.scp", "--synthetic=rirs/rir_list", "--width=2", "--batch-size=2", "--steps=1",
                      "--num-threads=1", "o_gan"},
                     "settings.txt"});
  }
  ASSERT_NO_FATAL_FAILURE(fit_eq_model_if_built());
  for (const Case& c : cases) {
    SCOPED_TRACE(c.program + " -> " + c.out);
    if (need(c.program).empty()) continue;
    sentinel(c.out + "/KEEP.txt");
    const Tree inputs = trees({"rirs", "data", "audio", "rooms.txt", "measured", "measured.scp", "diag_rooms.txt"});
    const Tree keep = tree(c.out);
    std::vector<std::string> argv = {need(c.program)};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    expect_refused(run(argv), c.out);
    EXPECT_NE(run(argv).output.find("--overwrite"), std::string::npos);
    EXPECT_EQ(tree(c.out), keep) << "a refused run changed its output location";
    std::vector<std::string> over = argv;
    over.insert(over.begin() + (c.program == "rir-eq" ? 2 : 1), "--overwrite");
    auto r = run(over);
    ASSERT_EQ(r.status, 0) << r.output;
    expect_unchanged(keep);
    EXPECT_TRUE(fs::exists(path(c.out + "/" + c.own_name)));
    if (c.program != "ts-rirgan-train") {  // its re-run over a checkpoint is --resume, tested apart
      r = run(argv);
      ASSERT_EQ(r.status, 0) << "a re-run into its own directory: " << r.output;
      expect_unchanged(keep);
      // A user's file under one of the program's names in a dir it owns: refused, not replaced.
      fs::remove(path(c.out + "/" + c.own_name));
      sentinel(c.out + "/" + c.own_name);
      const Tree mine = tree(c.out + "/" + c.own_name);
      expect_refused(run(argv), c.own_name);
      expect_unchanged(mine);
    }
    expect_unchanged(inputs);
  }
  expect_valid_data_dirs_point_at_existing_files();
}

// Outputs that are, contain or lie inside an input, for every program that reads RIR lists: the
// directory of the list, through a symlink, and a list whose wavs live elsewhere.
TEST_F(DataSafety, OutputsOverInputsAreRefused) {
  make_rirs("rirs", 16);
  make_data("data/in", "audio", 2);
  ASSERT_NO_FATAL_FAILURE(fit_eq_model_if_built());
  fs::create_directory_symlink(path("rirs"), path("rirs_link"));
  // A list in one place whose wavs are in another: the wavs are inputs too.
  fs::create_directories(path("lists"));
  write_bytes(path("lists/rir.scp"), read_bytes(path("rirs/rir.scp")));
  const Tree before = trees({"rirs", "data", "audio", "lists", "eq.model"});
  struct Case {
    std::string program;
    std::vector<std::string> args;
    std::string named;
  };
  const std::vector<Case> cases = {
      {"rir-eq", {"apply", "eq.model", "rirs/rir.scp", "rirs"}, "rirs"},
      {"rir-eq", {"apply", "eq.model", "lists/rir.scp", "rirs_link"}, "rirs"},
      {"rir-eq", {"apply", "eq.model", "lists/rir.scp", "."}, "rirs"},
      {"rir-eq", {"apply", "--overwrite", "eq.model", "rirs/rir.scp", "rirs/r0.wav"}, "rirs"},
      {"reverberate-data", {"--rir-set-parameters", "rirs_link/rir_list", "data/in", "rirs"}, "rirs"},
      {"reverberate-data", {"--rir-set-parameters", "rirs/rir_list", "--write-wavs=rirs_link", "data/in", "o"}, "rirs"},
      {"reverberate-data", {"--rir-set-parameters", "rirs/rir_list", "data/in", "audio"}, "audio"},
      {"rir-diagnose", {"rooms.txt", "rirs/rir.scp", "rirs"}, "rirs"},
      {"gas-to-real", {"--model=none", "rirs/rir.scp", "rirs_link"}, "rirs"},
  };
  write_bytes(path("rooms.txt"), "");
  for (const Case& c : cases) {
    if (need(c.program).empty()) continue;
    std::vector<std::string> argv = {need(c.program)};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    SCOPED_TRACE(c.program + " " + c.args.back());
    auto r = run(argv);
    EXPECT_NE(r.status, 0) << r.output;
    expect_unchanged(before);
  }
  // The refusals name the input (the ones whose checks come first are asserted exactly).
  if (!need("rir-eq").empty()) {
    expect_refused(run({need("rir-eq"), "apply", "eq.model", "lists/rir.scp", "rirs_link"}), "contains the input");
    expect_refused(run({need("rir-eq"), "apply", "--overwrite", "eq.model", "rirs/rir.scp", "rirs/r0.wav"}), "is the input");
    // A single output file that is an input (the list itself, or through a symlink).
    expect_refused(run({need("rir-eq"), "fit", "rirs/rir.scp", "rirs/rir.scp"}), "is an input");
    expect_refused(run({need("rir-eq"), "fit", "rirs/rir.scp", "rirs_link/r1.wav"}), "is an input");
    expect_refused(run({need("rir-eq"), "apply", "eq.model", "rirs/rir.scp", "."}), "contains the input");
  }
  EXPECT_FALSE(fs::exists(path("o")));
  expect_unchanged(before);
}

// A re-run replaces its own files and removes its own stale ones; a user's file beside them and a
// file the user changed since are left.
TEST_F(DataSafety, ReRunsReplaceOnlyTheirOwnFiles) {
  if (need("rir-simulate").empty()) GTEST_SKIP() << "rir-simulate not built";
  write_bytes(path("rooms3.txt"), "a room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.3\n"
                                  "b room=5,4,3 src=1,1,1.5 mic=3,2,1.2 t60=0.3\n"
                                  "c room=5,4,3 src=1,1,1.5 mic=3,1.5,1.2 t60=0.3\n");
  write_bytes(path("rooms1.txt"), "a room=5,4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=0.4\n");
  ASSERT_EQ(run({need("rir-simulate"), "rooms3.txt", "sim"}).status, 0);
  sentinel("sim/user.txt");
  write_bytes(path("sim/c.wav"), read_bytes(path("sim/c.wav")) + "edited");  // the user changed it
  const Tree keep = trees({"sim/user.txt", "sim/c.wav"});
  ASSERT_EQ(run({need("rir-simulate"), "rooms1.txt", "sim"}).status, 0);
  expect_unchanged(keep);
  EXPECT_FALSE(fs::exists(path("sim/b.wav"))) << "its own stale file stayed";
  EXPECT_TRUE(fs::exists(path("sim/a.wav")));
  EXPECT_EQ(read_bytes(path("sim/rir.scp")).find("b "), std::string::npos);
}

// Two runs at once sharing a --write-wavs directory: both complete, neither loses a file.
TEST_F(DataSafety, ConcurrentRunsSharingADirectory) {
  if (need("reverberate-data").empty()) GTEST_SKIP() << "reverberate-data not built";
  make_rirs("rirs", 4);
  make_data("data/a", "audio_a", 12, "spkA");
  make_data("data/b", "audio_b", 12, "spkB");
  robust::RunResult ra, rb;
  std::thread ta([&] { ra = rvb({"--write-wavs", "exp/wavs", "data/a", "exp/a"}); });
  std::thread tb([&] { rb = rvb({"--write-wavs", "exp/wavs", "data/b", "exp/b"}); });
  ta.join();
  tb.join();
  ASSERT_EQ(ra.status, 0) << ra.output;
  ASSERT_EQ(rb.status, 0) << rb.output;
  for (int i = 0; i < 12; ++i) {
    EXPECT_TRUE(fs::exists(path("exp/wavs/spkA-u" + std::to_string(i) + ".wav")));
    EXPECT_TRUE(fs::exists(path("exp/wavs/spkB-u" + std::to_string(i) + ".wav")));
  }
  const std::string marker = read_bytes(path("exp/wavs/.tsrir-owned"));
  EXPECT_NE(marker.find("spkA-u11.wav"), std::string::npos) << marker;
  EXPECT_NE(marker.find("spkB-u11.wav"), std::string::npos) << marker;
  expect_valid_data_dirs_point_at_existing_files();
}

// Ctrl-C and SIGKILL mid-run, into a directory holding a previous set and a user's file.
TEST_F(DataSafety, InterruptedRunsKeepSentinelsInputsAndValidDataDirs) {
  if (need("reverberate-data").empty()) GTEST_SKIP() << "reverberate-data not built";
  make_rirs("rirs", 4, 1, 8000);
  make_data("data/in", "audio", 40, "spk1", 2.0);
  ASSERT_EQ(rvb({"--num-threads=1", "--write-wavs", "exp/wavs", "data/in", "exp/out"}).status, 0);
  sentinel("exp/wavs/KEEP");
  sentinel("exp/out/KEEP");
  const Tree before = trees({"rirs", "data", "audio", "exp/wavs/KEEP", "exp/out/KEEP"});
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(rvb({"--num-threads=1", "--write-wavs", "exp/wavs", "data/in", "exp/out"}).status, 0);
  const double full_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::mt19937 rng(14);
  int killed = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const int sig = trial % 2 ? SIGKILL : SIGINT;
    const double delay = std::uniform_real_distribution<double>(0.1, 0.8)(rng) * full_s;
    SCOPED_TRACE(std::string(sig == SIGINT ? "SIGINT" : "SIGKILL") + " after " + std::to_string(delay) + " s");
    // Alternately into the existing owned directories and into new ones.
    const std::string wavs = trial < 2 ? "exp/wavs" : "exp/wavs" + std::to_string(trial);
    const std::string out = trial < 2 ? "exp/out" : "exp/out" + std::to_string(trial);
    pid_t pid = fork();
    if (pid == 0) {
      if (!std::freopen("/dev/null", "w", stdout) || !std::freopen(path("kill.log").c_str(), "w", stderr)) _exit(126);
      execl(need("reverberate-data").c_str(), "reverberate-data", "--rir-set-parameters", "rirs/rir_list",
            "--random-seed=3", "--num-threads=1", "--write-wavs", wavs.c_str(), "data/in", out.c_str(),
            static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    killed += WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0);
    SCOPED_TRACE("pid " + std::to_string(pid) + " status " + std::to_string(status) + ": " + read_bytes(path("kill.log")));
    expect_unchanged(before);
    expect_valid_data_dirs_point_at_existing_files();
    if (sig == SIGINT) {
      for (const auto& e : fs::recursive_directory_iterator(dir_))
        EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << "Ctrl-C left " << e.path();
    }
    // The same command again completes (a SIGKILL's staging leftovers do not stand in the way).
    auto again = rvb({"--num-threads=1", "--write-wavs", wavs, "data/in", out});
    ASSERT_EQ(again.status, 0) << again.output;
    expect_unchanged(before);
  }
  EXPECT_GE(killed, 1) << "every run finished before its kill";
  expect_valid_data_dirs_point_at_existing_files();
}

// A failed --write-wavs run leaves no directory it created behind (issue item 3).
TEST_F(DataSafety, FailedRunLeavesNoEmptyParentDirectory) {
  if (need("reverberate-data").empty()) GTEST_SKIP() << "reverberate-data not built";
  make_rirs("rirs", 2);
  make_data("data/in", "audio", 2);
  write_bytes(path("data/in/wav.scp"), read_bytes(path("data/in/wav.scp")) + "spk1-u9 false |\n");
  write_bytes(path("data/in/utt2spk"), read_bytes(path("data/in/utt2spk")) + "spk1-u9 spk1\n");
  write_bytes(path("data/in/spk2utt"), "spk1 spk1-u0 spk1-u1 spk1-u9\n");
  auto r = rvb({"--write-wavs", "new/deep/wavs", "data/in", "new2/out"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_FALSE(fs::exists(path("new"))) << "the failed run left an empty directory";
  EXPECT_FALSE(fs::exists(path("new2")));
}

// One CRLF policy (issue 14): a data dir with DOS line endings is the same error, naming the file
// and line, from validate-data-dir and from reverberate-data; RIR lists with them are read as
// Kaldi's reverberate_data_dir.py reads them (the '\r' dropped).
TEST_F(DataSafety, CrlfDataDirIsOneErrorEverywhere) {
  if (need("reverberate-data").empty() || need("validate-data-dir").empty()) GTEST_SKIP() << "programs not built";
  make_rirs("rirs", 2);
  make_data("data/in", "audio", 2);
  const std::string wav_scp = read_bytes(path("data/in/wav.scp"));
  std::string crlf;
  for (char c : wav_scp) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_bytes(path("data/in/wav.scp"), crlf);
  auto v = run({need("validate-data-dir"), "data/in"});
  EXPECT_NE(v.status, 0) << v.output;
  EXPECT_NE(v.output.find("data/in/wav.scp:1: carriage return"), std::string::npos) << v.output;
  auto r = rvb({"data/in", "out"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("data/in/wav.scp:1: carriage return"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out")));
  // The RIR list with CRLF: accepted, as Kaldi accepts it.
  write_bytes(path("data/in/wav.scp"), wav_scp);
  const std::string list = read_bytes(path("rirs/rir_list"));
  std::string list_crlf;
  for (char c : list) list_crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_bytes(path("rirs/rir_list"), list_crlf);
  r = rvb({"data/in", "out"});
  EXPECT_EQ(r.status, 0) << r.output;
}

// Room ids travel with the RIRs whichever list form a program is given (issue 14, item 3): an scp
// has none, so the rir_list beside it gives them; an scp without one is each RIR its own room, with
// a warning; an scp whose ids the list beside it lacks is an error naming both.
using FirstContact = DataSafety;
TEST_F(FirstContact, RoomIdsTravelWithScpInputs) {
  if (need("rir-eq").empty()) GTEST_SKIP() << "rir-eq not built";
  make_rirs("rirs", 16);
  ASSERT_EQ(run({need("rir-eq"), "fit", "rirs/rir.scp", "eq.model"}).status, 0);
  auto rooms_of = [&](const std::string& list) {
    std::map<std::string, std::string> rooms;
    std::istringstream in(read_bytes(path(list)));
    for (std::string id, room, x; in >> x >> id >> x >> room;) {
      std::getline(in, x);
      rooms[id] = room;
    }
    return rooms;
  };
  const auto expected = rooms_of("rirs/rir_list");
  ASSERT_EQ(expected.at("r3"), "room1");
  std::vector<std::vector<std::string>> programs = {{need("rir-eq"), "apply", "eq.model"}};
  if (!need("ts-rirgan-train").empty() && !need("gas-to-real").empty()) {
    ASSERT_EQ(run({need("ts-rirgan-train"), "--real=rirs/rir.scp", "--synthetic=rirs/rir_list", "--width=2",
                   "--batch-size=2", "--steps=1", "--num-threads=1", "model"}).status, 0);
    programs.push_back({need("gas-to-real"), "--model=model"});
  }
  int n = 0;
  for (auto argv : programs) {
    const std::string out = "out" + std::to_string(n++);
    argv.push_back("rirs/rir.scp");
    argv.push_back(out);
    auto r = run(argv);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(rooms_of(out + "/rir_list"), expected) << argv[0];
  }
  // Without a rir_list beside the scp: one room per RIR, said on stderr.
  fs::create_directories(path("alone"));
  write_bytes(path("alone/rir.scp"), read_bytes(path("rirs/rir.scp")));
  auto r = run({need("rir-eq"), "apply", "eq.model", "alone/rir.scp", "out_alone"});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("no rir_list beside it"), std::string::npos) << r.output;
  EXPECT_EQ(rooms_of("out_alone/rir_list").at("r3"), "r3");
  // A rir_list beside that does not hold the scp's ids: an error naming it.
  write_bytes(path("alone/rir_list"), "--rir-id other --room-id x rirs/r0.wav\n");
  r = run({need("rir-eq"), "apply", "eq.model", "alone/rir.scp", "out_bad"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("alone/rir_list"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out_bad")));
}

}  // namespace
