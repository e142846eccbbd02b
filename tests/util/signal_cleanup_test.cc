// The interruption handler removes registered temporaries without touching the heap: SIGINT may
// land inside malloc (rir-simulate's workers allocate constantly), and a handler that allocates
// then aborts with "malloc assertion failure" instead of dying by SIGINT.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "util/cleanup.h"
#include "util/program.h"

namespace fs = std::filesystem;
using namespace tsrir;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A staging tree like owned_output's: many files (more than one getdents buffer) and nested dirs.
void make_tree(const fs::path& root) {
  fs::create_directories(root / "wav" / "deeper");
  for (int i = 0; i < 300; ++i) std::ofstream(root / "wav" / ("utt_with_a_long_name_" + std::to_string(i) + ".wav")) << i;
  std::ofstream(root / "wav" / "deeper" / "x") << "x";
  std::ofstream(root / "wav.scp") << "a a.wav\n";
}

}  // namespace

TEST(SignalCleanup, RemovesARegisteredTreeAndNothingElse) {
  const fs::path dir = fresh_dir("tsrir_signal_cleanup_tree");
  const fs::path staging = dir / ".tsrir-staging.tmp.1.0";
  const fs::path temp_file = dir / "out.scp.tmp.1";
  make_tree(staging);
  std::ofstream(temp_file) << "partial";
  std::ofstream(dir / "users_file") << "keep";
  register_temp_path(staging.string());
  register_temp_path(temp_file.string());
  remove_registered_temps_on_signal();
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_FALSE(fs::exists(temp_file));
  EXPECT_TRUE(fs::exists(dir / "users_file"));
  fs::remove_all(dir);
}

TEST(SignalCleanup, DoesNotFollowASymlinkOutOfTheTree) {
  const fs::path dir = fresh_dir("tsrir_signal_cleanup_link");
  const fs::path staging = dir / "staging.tmp.1";
  fs::create_directories(staging);
  fs::create_directories(dir / "users");
  std::ofstream(dir / "users" / "data") << "keep";
  fs::create_directory_symlink(dir / "users", staging / "link");
  register_temp_path(staging.string());
  remove_registered_temps_on_signal();
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_TRUE(fs::exists(dir / "users" / "data"));
  fs::remove_all(dir);
}

// SIGINT delivered while worker threads allocate: the program dies by SIGINT with its staging
// tree gone, every time. The allocating handler this replaces failed this within a few trials.
TEST(SignalCleanup, SigintDuringHeavyAllocationDiesBySigintAndRemovesTemps) {
  const fs::path dir = fresh_dir("tsrir_signal_cleanup_malloc");
  const int trials = 30;
  for (int trial = 0; trial < trials; ++trial) {
    const fs::path staging = dir / ("staging.tmp." + std::to_string(trial));
    make_tree(staging);
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      close(ready[0]);
      const int status = run_program("signal_cleanup_test", [&] {
        register_temp_path(staging.string());
        std::atomic<bool> stop{false};
        std::vector<std::thread> workers;
        for (int t = 0; t < 3; ++t)
          workers.emplace_back([&stop, t] {
            std::vector<std::vector<char>> blocks(64);
            for (unsigned i = 0; !stop; ++i) blocks[i % 64].assign(16 + (i * 7919u + t) % 200000, 'x');
          });
        const char byte = 1;
        if (write(ready[1], &byte, 1) != 1) _exit(3);
        std::vector<std::vector<char>> blocks(64);
        for (unsigned i = 0;; ++i) blocks[i % 64].assign(16 + (i * 104729u) % 300000, 'y');
        return 0;
      });
      _exit(status);
    }
    close(ready[1]);
    char byte = 0;
    ASSERT_EQ(read(ready[0], &byte, 1), 1);
    close(ready[0]);
    std::this_thread::sleep_for(std::chrono::microseconds(500 + 997 * (trial % 13)));
    kill(pid, SIGINT);
    // A handler that allocates may also deadlock on malloc's lock: bound the wait.
    int status = 0;
    pid_t waited = 0;
    for (int ms = 0; ms < 10000 && (waited = waitpid(pid, &status, WNOHANG)) == 0; ms += 10)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (waited == 0) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      FAIL() << "trial " << trial << ": still running 10 s after SIGINT (deadlocked in the handler?)";
    }
    ASSERT_EQ(waited, pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "trial " << trial << ": exited with " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), SIGINT) << "trial " << trial << ": died by signal " << WTERMSIG(status);
    EXPECT_FALSE(fs::exists(staging)) << "trial " << trial;
  }
  fs::remove_all(dir);
}
