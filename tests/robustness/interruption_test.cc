// Interrupted runs. Each long-running program gets a small workload that takes about a second,
// runs once to completion (the baseline), then several times killed at seeded random points with
// SIGINT or SIGKILL, into a fresh location or over the previous complete output, each time
// followed by the same command run again. Checks:
//  - after a kill, every final-named output either does not exist or is byte-identical to the
//    baseline (complete; never truncated, never half-written; the runs are deterministic for a
//    fixed seed and thread count, so "complete" can be checked byte for byte);
//  - a previous complete output survives a killed run that would have replaced it;
//  - after SIGINT, no temporary (".tmp.") is left anywhere (the handler removes them); after
//    SIGKILL temporaries may stay, but only under ".tmp." names, and the re-run copes with them;
//  - the re-run exits 0 and produces exactly the baseline;
//  - ts-rirgan-train killed with SIGKILL and re-run with --resume continues from its last
//    checkpoint: the final loss log equals the uninterrupted run's.
//  - rir-diagnose's reported run time is the one part of its output that differs between
//    complete runs; it is masked before comparing (see mask_run_time).
// Programs not built in this build (e.g. ts-rirgan-train without LibTorch) are skipped by name.
// TSRIR_INTERRUPT_TRIALS (default 4) and TSRIR_INTERRUPT_SEED vary the kill points
// (tests/robustness/run_interrupts.sh runs many more).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <random>
#include <thread>

#include "robust_test_util.h"

namespace fs = std::filesystem;
using robust::make_wav;
using robust::synthetic_rir;
using robust::WavSpec;

namespace {

using Snapshot = std::map<std::string, std::string>;  // relative path -> bytes

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

class Interruption : public robust::ScratchDirTest {
 protected:
  struct Job {
    std::string program;                 // in TSRIR_BIN_DIR
    std::vector<std::string> args;
    std::vector<std::string> outputs;    // final-named outputs (files or directories) under dir_
    // Masks what legitimately differs between complete runs (a measured run time), given the
    // output's relative path and bytes; the rest is compared byte for byte.
    std::function<std::string(const std::string&, std::string)> normalise = nullptr;
  };

  Snapshot snapshot(const Job& job) const {
    Snapshot s;
    for (const auto& out : job.outputs) {
      const fs::path p = dir_ / out;
      if (fs::is_directory(p)) {
        // The ownership marker records times and sizes, not output, and a killed run's staging
        // directory (".tsrir-staging.tmp.<pid>.<n>") is a temporary: both left out.
        for (const auto& e : fs::recursive_directory_iterator(p)) {
          const std::string rel = fs::relative(e.path(), dir_).string();
          if (e.is_regular_file() && e.path().filename() != ".tsrir-owned" && rel.find(".tmp.") == std::string::npos)
            s[rel] = read_bytes(e.path().string());
        }
      } else if (fs::exists(p)) {
        s[out] = read_bytes(p.string());
      }
    }
    if (job.normalise) {
      for (auto& [rel, bytes] : s) bytes = job.normalise(rel, std::move(bytes));
    }
    return s;
  }

  std::vector<std::string> temporaries() const {
    std::vector<std::string> t;
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      if (e.path().filename().string().find(".tmp.") != std::string::npos) t.push_back(e.path().string());
    return t;
  }

  void remove_outputs(const Job& job) const {
    for (const auto& out : job.outputs) fs::remove_all(dir_ / out);
  }

  std::vector<std::string> argv_of(const Job& job) const {
    std::vector<std::string> argv = {robust::program_path(job.program)};
    argv.insert(argv.end(), job.args.begin(), job.args.end());
    return argv;
  }

  // Starts the job, sends `sig` after `delay_s` (if still running), returns the exit status
  // (128 + signal when killed). With `ready_path`, the delay starts once that file exists.
  int run_and_kill(const Job& job, int sig, double delay_s, const std::string& ready_path = "") const {
    const auto argv = argv_of(job);
    pid_t pid = fork();
    if (pid == 0) {
      const std::string log = (dir_ / (job.program + ".log")).string();
      FILE* f = std::freopen(log.c_str(), "a", stderr);
      (void)f;
      if (!std::freopen("/dev/null", "w", stdout)) _exit(126);
      std::vector<char*> a;
      for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
      a.push_back(nullptr);
      execv(a[0], a.data());
      _exit(127);
    }
    auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(delay_s);
    bool ready = ready_path.empty();
    int status = 0;
    for (;;) {
      pid_t r = waitpid(pid, &status, WNOHANG);
      if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      if (!ready && fs::exists(ready_path)) {
        ready = true;
        deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(delay_s);
      }
      if (ready && std::chrono::steady_clock::now() >= deadline) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill(pid, sig);
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

  std::string log_of(const Job& job) const { return read_bytes((dir_ / (job.program + ".log")).string()); }

  // The whole protocol for one job whose runs are deterministic.
  void check_interruptions(const Job& job) {
    if (robust::program_path(job.program).empty()) GTEST_SKIP() << job.program << " is not built in this build";
    remove_outputs(job);
    const auto t0 = std::chrono::steady_clock::now();
    robust::RunResult base = robust::run_argv(argv_of(job));
    // The shortest complete run seen so far: kill points are drawn inside it, so that a run
    // slowed by a busy machine (ctest -j) does not push them past the end of faster runs.
    double full_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(base.status, 0) << base.output;
    const Snapshot baseline = snapshot(job);
    ASSERT_FALSE(baseline.empty()) << job.program << " wrote none of its outputs";
    ASSERT_TRUE(temporaries().empty()) << "a successful run left temporaries: " << temporaries()[0];

    const int trials = env_int("TSRIR_INTERRUPT_TRIALS", 4);
    std::mt19937 rng(static_cast<unsigned>(env_int("TSRIR_INTERRUPT_SEED", 20261121)) + std::hash<std::string>()(job.program) % 1000);
    std::uniform_real_distribution<double> when(0.02, 0.8);
    int killed = 0;
    for (int trial = 0; trial < trials; ++trial) {
      const int sig = trial % 2 == 0 ? SIGINT : SIGKILL;
      // Every other pair of trials runs over the complete output of the previous run, which must
      // survive the kill (an output is replaced only by a complete one).
      const bool over_existing = (trial / 2) % 2 == 1;
      const double delay = when(rng) * full_s;
      SCOPED_TRACE(job.program + (sig == SIGINT ? " SIGINT" : " SIGKILL") + " after " + std::to_string(delay) +
                   " s of ~" + std::to_string(full_s) + " s" + (over_existing ? ", over an existing output" : ""));
      if (!over_existing) remove_outputs(job);
      ASSERT_TRUE(!over_existing || snapshot(job) == baseline);
      const int status = run_and_kill(job, sig, delay);
      if (status != 0) ++killed;
      // Either nothing or everything under the final names.
      const Snapshot after = snapshot(job);
      for (const auto& [rel, bytes] : after) {
        auto it = baseline.find(rel);
        ASSERT_TRUE(it != baseline.end()) << "unexpected final-named output " << rel;
        ASSERT_TRUE(it->second == bytes) << "final-named output differs from a complete run (truncated?): " << rel;
      }
      if (over_existing) {
        EXPECT_TRUE(after == baseline) << "the previous complete output was lost or changed";
      }
      if (status == 0) {
        EXPECT_EQ(after, baseline) << "exit 0 but incomplete output";
      } else {
        EXPECT_EQ(status, 128 + sig) << log_of(job);
      }
      if (sig == SIGINT) {
        const auto temps = temporaries();
        EXPECT_TRUE(temps.empty()) << "SIGINT left a temporary: " << temps[0];
      }
      // Re-running the same command completes the job, whatever the kill left behind.
      const auto t1 = std::chrono::steady_clock::now();
      robust::RunResult again = robust::run_argv(argv_of(job));
      full_s = std::min(full_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count());
      ASSERT_EQ(again.status, 0) << again.output;
      EXPECT_TRUE(snapshot(job) == baseline) << "re-run after the kill differs from the baseline";
      for (const auto& t : temporaries()) fs::remove_all(t);  // SIGKILL leftovers
    }
    // The kill points are spread over the run: at least one must have landed mid-run, or this
    // test checked nothing.
    EXPECT_GE(killed, 1) << "every run finished before its kill";
    std::cerr << job.program << ": " << killed << " of " << trials << " runs killed mid-way (full run " << full_s
              << " s)\n";
  }

  // Inputs shared by the jobs below.
  void make_rir_set(const std::string& name, int count, unsigned seed, size_t length = 8000) {
    fs::create_directories(dir_ / name);
    std::mt19937 rng(seed);
    std::string scp;
    for (int i = 0; i < count; ++i) {
      const std::string id = name + "_" + std::to_string(i);
      const std::string p = (dir_ / name / (id + ".wav")).string();
      write_bytes(p, make_wav({}, synthetic_rir(rng, 0.2 + 0.05 * (i % 8), length)));
      scp += id + " " + p + "\n";
    }
    write_bytes((dir_ / name / "rir.scp").string(), scp);
  }
  void make_speech_dir(const std::string& name, int count, double seconds) {
    fs::create_directories(dir_ / name);
    std::string wav, u2s, s2u;
    for (int i = 0; i < count; ++i) {
      char id[32];
      std::snprintf(id, sizeof id, "spk1-utt%03d", i);
      const std::string p = (dir_ / name / (std::string(id) + ".wav")).string();
      write_bytes(p, make_wav({}, robust::test_tone(static_cast<size_t>(seconds * 16000), 200.0 + 10 * i)));
      wav += std::string(id) + " " + p + "\n";
      u2s += std::string(id) + " spk1\n";
      s2u += (s2u.empty() ? "spk1" : "") + std::string(" ") + id;
    }
    write_bytes((dir_ / name / "wav.scp").string(), wav);
    write_bytes((dir_ / name / "utt2spk").string(), u2s);
    write_bytes((dir_ / name / "spk2utt").string(), s2u + "\n");
  }
};

TEST_F(Interruption, RirSimulate) {
  std::string rooms;
  for (int i = 0; i < 80; ++i) {
    rooms += "r" + std::to_string(i) + " room=" + std::to_string(5 + i % 4) + ",4,3 src=1,1,1.5 mic=3,2.5,1.2 t60=" +
             std::to_string(0.3 + 0.05 * (i % 6)) + "\n";
  }
  write_bytes(path("rooms.txt"), rooms);
  check_interruptions({"rir-simulate", {"--num-threads=1", "--seed=3", path("rooms.txt"), path("sim")}, {"sim"}});
}

TEST_F(Interruption, RirMetrics) {
  make_rir_set("set", 300, 1, 16000);
  check_interruptions({"rir-metrics",
                       {"--bands", "--num-threads=1", "--output=" + path("metrics.txt"), path("set/rir.scp")},
                       {"metrics.txt"}});
}

TEST_F(Interruption, RirEqFitAndApply) {
  make_rir_set("real", 120, 2);
  make_rir_set("sim", 200, 3);
  check_interruptions({"rir-eq", {"fit", "--sample-rate=16000", path("real/rir.scp"), path("eq.model")}, {"eq.model"}});
  check_interruptions({"rir-eq", {"apply", "--seed=7", "--num-threads=1", path("eq.model"), path("sim/rir.scp"), path("sim_eq")},
                       {"sim_eq"}});
}

TEST_F(Interruption, ReverberateData) {
  make_rir_set("rirs", 10, 4);
  make_speech_dir("data", 100, 3.0);
  check_interruptions({"reverberate-data",
                       {"--rir-set-parameters", path("rirs/rir.scp"), "--random-seed=5", "--num-threads=1",
                        "--write-wavs=" + path("rvb_wavs"), path("data"), path("data_rvb")},
                       {"data_rvb", "rvb_wavs"}});
}

TEST_F(Interruption, WavReverberate) {
  make_rir_set("rirs", 1, 5, 16000);
  write_bytes(path("long.wav"), make_wav({}, robust::test_tone(16000 * 600)));  // 10 minutes
  check_interruptions({"wav-reverberate",
                       {"--print-args=false", "--impulse-response=" + path("rirs/rirs_0.wav"), path("long.wav"), path("out.wav")},
                       {"out.wav"}});
}

// rir-diagnose writes findings.json, report.html and extended_models into one directory swapped in
// at the end. Its analysis is deterministic for a fixed seed and thread count, except the run time
// it reports ("seconds" in findings.json, "...; 0.323 s." in report.html): that number is masked,
// everything else is compared byte for byte.
std::string mask_run_time(const std::string& rel, std::string bytes) {
  auto mask_after = [&](const std::string& anchor, const std::string& stop) {
    const size_t a = bytes.find(anchor);
    if (a == std::string::npos) return;
    const size_t from = a + anchor.size();
    const size_t to = bytes.find(stop, from);
    if (to != std::string::npos) bytes.replace(from, to - from, "<run time>");
  };
  if (rel.size() >= 13 && rel.compare(rel.size() - 13, 13, "findings.json") == 0) mask_after("\"seconds\": ", "\n");
  if (rel.size() >= 11 && rel.compare(rel.size() - 11, 11, "report.html") == 0) mask_after("held-out RIRs; ", " s.</p>");
  return bytes;
}

TEST_F(Interruption, RirDiagnose) {
  // 24 "measured" RIRs of 1 s: ~0.4 s of simulation and analysis on one thread (the protocol runs
  // it 9 times; the test stays under ~5 s).
  std::vector<std::string> ids, wavs;
  fs::create_directories(dir_ / "measured");
  for (int i = 0; i < 24; ++i) {
    ids.push_back("m" + std::to_string(i));
    wavs.push_back(path("measured/m" + std::to_string(i) + ".wav"));
  }
  robust::write_diagnose_inputs(ids, wavs, path("rooms.txt"), path("measured.scp"), 16000);
  Job job{"rir-diagnose",
          {"--num-threads=1", "--seed=3", path("rooms.txt"), path("measured.scp"), path("diag")},
          {"diag"},
          mask_run_time};
  check_interruptions(job);
  // The mask must not hide a difference of substance: it replaced exactly one number per file.
  const Snapshot s = snapshot(job);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NE(s.at("diag/findings.json").find("\"seconds\": <run time>\n"), std::string::npos);
  EXPECT_NE(s.at("diag/report.html").find("held-out RIRs; <run time> s.</p>"), std::string::npos);
}

TEST_F(Interruption, RirRoomList) {
  // 20000 set-ups: ~0.1 s, enough to land kills while the list is being written.
  std::string table = "rir-id Lx Ly Lz sx sy sz mx my mz room-id\n";
  for (int i = 0; i < 20000; ++i) {
    table += "r" + std::to_string(i) + " 6 4 3 1 1 1.5 " + std::to_string(2 + (i % 30) * 0.1) + " 2.5 1.2 room" +
             std::to_string(i % 7) + "\n";
  }
  write_bytes(path("setups.txt"), table);
  check_interruptions({"rir-room-list", {"--seed=4", path("setups.txt"), path("rooms.txt")}, {"rooms.txt"}});
}

TEST_F(Interruption, GanTrainingResumesFromLastCheckpoint) {
  const std::string prog = robust::program_path("ts-rirgan-train");
  if (prog.empty()) GTEST_SKIP() << "ts-rirgan-train is not built in this build (LibTorch off)";
  make_rir_set("real", 4, 6);
  make_rir_set("syn", 4, 7);
  auto train = [&](const std::string& model, bool resume) {
    std::vector<std::string> a = {prog, "--real=" + path("real/rir.scp"), "--synthetic=" + path("syn/rir.scp"),
                                  "--width=2", "--batch-size=2", "--num-threads=1", "--seed=3", "--steps=12",
                                  "--checkpoint-every=1"};
    if (resume) a.push_back("--resume");
    a.push_back(path(model));
    return a;
  };
  const auto t0 = std::chrono::steady_clock::now();
  robust::RunResult base = robust::run_argv(train("base", false));
  const double full_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(base.status, 0) << base.output;
  // The losses must match exactly; the last column (step_s, wall time) cannot.
  auto losses = [&](const std::string& model) {
    std::istringstream in(read_bytes(path(model + "/loss_log.csv")));
    std::string out;
    for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  const std::string base_log = losses("base");
  ASSERT_NE(base_log.find("\n12,"), std::string::npos) << base_log;
  std::mt19937 rng(static_cast<unsigned>(env_int("TSRIR_INTERRUPT_SEED", 20261121)));
  // The kill lands at a random point after the first checkpoint exists (before it, --resume has
  // nothing to resume: that case is the plain re-run the other programs test).
  // Start-up (LibTorch, data) takes at most ~3/4 of the baseline run, so the 11 steps after the
  // first checkpoint last more than a fifth of it.
  std::uniform_real_distribution<double> when(0.0, 0.2 * full_s);
  const int trials = std::max(1, env_int("TSRIR_INTERRUPT_TRIALS", 4) / 4);
  for (int trial = 0; trial < trials; ++trial) {
    const std::string model = "m" + std::to_string(trial);
    const double delay = when(rng);
    SCOPED_TRACE("SIGKILL " + std::to_string(delay) + " s after the first checkpoint (full run ~" +
                 std::to_string(full_s) + " s)");
    const auto argv = train(model, false);
    Job job{"ts-rirgan-train", std::vector<std::string>(argv.begin() + 1, argv.end()), {}};
    const int status = run_and_kill(job, SIGKILL, delay, path(model + "/checkpoint.pt"));
    EXPECT_EQ(status, 128 + SIGKILL) << "training finished before the kill: the workload is too small";
    // The user's next command: --resume. The checkpoint must load (never truncated).
    ASSERT_TRUE(fs::exists(path(model + "/checkpoint.pt")));
    robust::RunResult again = robust::run_argv(train(model, true));
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_NE(again.output.find("resumed"), std::string::npos) << again.output;
    EXPECT_EQ(losses(model), base_log) << "resumed training diverged from the uninterrupted run";
    for (const auto& t : temporaries()) fs::remove_all(t);
  }
}

TEST_F(Interruption, GasToReal) {
  const std::string train = robust::program_path("ts-rirgan-train");
  if (train.empty() || robust::program_path("gas-to-real").empty()) GTEST_SKIP() << "GAN programs not built (LibTorch off)";
  make_rir_set("real", 4, 8);
  make_rir_set("syn", 300, 9);
  robust::RunResult r = robust::run_argv({train, "--real=" + path("real/rir.scp"), "--synthetic=" + path("syn/rir.scp"),
                                          "--width=2", "--batch-size=2", "--num-threads=1", "--steps=1", path("model")});
  ASSERT_EQ(r.status, 0) << r.output;
  check_interruptions({"gas-to-real", {"--model=" + path("model"), path("syn/rir.scp"), path("translated")}, {"translated"}});
}

}  // namespace
