// What many test suites need, once: a scratch directory per test (removed afterwards) and running
// a built program or a shell command with its exit status, stdout and stderr captured.
// Header-only (link nothing; the CMake target tsrir_test_common only adds the include path).
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace tsrir_test {

// A whole file (binary); "" when it cannot be read.
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A fresh directory under the system temp dir, named after `tag` (default: the running test), the
// process and a counter.
inline std::filesystem::path make_scratch_dir(const std::string& tag = "") {
  static std::atomic<int> counter{0};
  std::string name = tag;
  if (name.empty()) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    name = info ? std::string(info->test_suite_name()) + "_" + info->name() : "none";
    for (char& c : name) {
      if (c == '/') c = '_';  // parameterised tests
    }
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("tsrir_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag = "") : dir_(make_scratch_dir(tag)) {}
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Writes `text` (binary, as is) to path(name) and returns that path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  std::string read(const std::string& name) const { return slurp(path(name)); }
  bool exists(const std::string& name) const { return std::filesystem::exists(path(name)); }

 private:
  std::filesystem::path dir_;
};

// A test fixture with a fresh directory per test: path(), write_text(), read_text(), dir_.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = make_scratch_dir(); }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write_text(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
  }
  std::string read_text(const std::string& name) const { return slurp(path(name)); }
  std::filesystem::path dir_;
};

struct CommandResult {
  int status = -1;  // exit status; -1 when killed by a signal
  std::string out, err;
};

// Runs `command` with /bin/sh, capturing stdout and stderr.
inline CommandResult run_command(const std::string& command) {
  ScratchDir scratch("run");
  const std::string out = scratch.path("stdout"), err = scratch.path("stderr");
  const int raw = std::system((command + " >'" + out + "' 2>'" + err + "'").c_str());
  CommandResult r;
  r.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

#ifdef TSRIR_BIN_DIR
// A program of this build: TSRIR_BIN_DIR/<name>.
inline std::string program_path(const std::string& name) { return std::string(TSRIR_BIN_DIR) + "/" + name; }
#endif

}  // namespace tsrir_test
