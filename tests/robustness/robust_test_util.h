// Helpers shared by the robustness tests: a scratch directory per test, WAV bytes written by hand
// (independent of the toolkit's writer, so a header can lie on purpose), and running a program
// with its exit status and output.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace robust {

class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write_bytes(const std::string& p, const std::string& bytes) const;
  std::string read_bytes(const std::string& p) const;
  std::filesystem::path dir_;
};

// A canonical 44-byte-header PCM WAV; the size fields can be overridden to lie.
struct WavSpec {
  uint16_t format_tag = 1;      // 1 = PCM, 3 = float
  uint16_t channels = 1;
  uint32_t sample_rate = 16000;
  uint16_t bits = 16;
  int64_t riff_size = -1;       // -1: correct value
  int64_t data_size = -1;       // -1: correct value
};
std::string make_wav(const WavSpec& spec, const std::vector<int16_t>& samples);
std::vector<int16_t> test_tone(size_t n, double freq_hz = 440.0, double rate_hz = 16000.0);
// A decaying noise RIR made here, independently of the simulator: a direct peak at sample 40,
// then Gaussian noise decaying by 60 dB in t60_s.
std::vector<int16_t> synthetic_rir(std::mt19937& rng, double t60_s, size_t n, double rate_hz = 16000.0);

// rir-diagnose inputs: one "measured" RIR per id (synthetic_rir, `length` samples at 16 kHz,
// T60 0.3-0.55 s) written to wavs[i], a room list stating each set-up (a 6 x 4 x 3 m room, the
// microphone moving along x) and an scp of "<id> <wav>".
void write_diagnose_inputs(const std::vector<std::string>& ids, const std::vector<std::string>& wavs,
                           const std::string& room_list, const std::string& scp, size_t length = 8000);
// The room-list line write_diagnose_inputs states for RIR `index`.
std::string diagnose_room_line(const std::string& id, size_t index);

struct RunResult {
  int status = -1;      // exit status, or 128 + signal
  std::string output;   // stdout and stderr together
};
// Runs argv directly (no shell), output captured.
RunResult run_argv(const std::vector<std::string>& argv);

// Path of a built program ($TSRIR_TEST_BIN_DIR, else TSRIR_BIN_DIR), or "" when it is not built
// (the caller then GTEST_SKIP()s).
std::string program_path(const std::string& name);

// Peak resident set size of finished children (ru_maxrss of RUSAGE_CHILDREN), in MB.
double children_peak_rss_mb();

}  // namespace robust
