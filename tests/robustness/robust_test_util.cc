#include "robust_test_util.h"

#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace robust {

void ScratchDirTest::SetUp() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  dir_ = std::filesystem::temp_directory_path() /
         ("tsrir_robust_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir_);
  std::filesystem::create_directories(dir_);
}

void ScratchDirTest::TearDown() { std::filesystem::remove_all(dir_); }

void ScratchDirTest::write_bytes(const std::string& p, const std::string& bytes) const {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << p;
}

std::string ScratchDirTest::read_bytes(const std::string& p) const {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

namespace {
void put(std::string& b, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
}  // namespace

std::string make_wav(const WavSpec& s, const std::vector<int16_t>& samples) {
  const uint32_t data = static_cast<uint32_t>(samples.size() * 2);
  std::string b = "RIFF";
  put(b, s.riff_size >= 0 ? static_cast<uint64_t>(s.riff_size) : 36 + data, 4);
  b += "WAVEfmt ";
  put(b, 16, 4);
  put(b, s.format_tag, 2);
  put(b, s.channels, 2);
  put(b, s.sample_rate, 4);
  put(b, static_cast<uint64_t>(s.sample_rate) * s.channels * (s.bits / 8), 4);
  put(b, static_cast<uint64_t>(s.channels) * (s.bits / 8), 2);
  put(b, s.bits, 2);
  b += "data";
  put(b, s.data_size >= 0 ? static_cast<uint64_t>(s.data_size) : data, 4);
  for (int16_t v : samples) put(b, static_cast<uint16_t>(v), 2);
  return b;
}

std::vector<int16_t> test_tone(size_t n, double freq_hz, double rate_hz) {
  std::vector<int16_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<int16_t>(std::lround(8000.0 * std::sin(2 * M_PI * freq_hz * i / rate_hz)));
  return v;
}

std::vector<int16_t> synthetic_rir(std::mt19937& rng, double t60_s, size_t n, double rate_hz) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<int16_t> v(n, 0);
  const size_t onset = 40;
  if (n <= onset) return v;
  v[onset] = 20000;
  for (size_t i = onset + 1; i < n; ++i) {
    const double t = (i - onset) / rate_hz;
    v[i] = static_cast<int16_t>(
        std::lround(std::clamp(3000.0 * std::pow(10.0, -3.0 * t / t60_s) * normal(rng), -32767.0, 32767.0)));
  }
  return v;
}

std::string diagnose_room_line(const std::string& id, size_t index) {
  char line[160];
  std::snprintf(line, sizeof line, " room=6,4,3 src=1,1,1.5 mic=%.2f,2.5,1.2 t60=%.2f", 2.0 + 0.08 * (index % 45),
                0.3 + 0.05 * (index % 6));
  return id + line;
}

void write_diagnose_inputs(const std::vector<std::string>& ids, const std::vector<std::string>& wavs,
                           const std::string& room_list, const std::string& scp, size_t length) {
  std::mt19937 rng(17);
  std::ofstream rooms(room_list, std::ios::binary), list(scp, std::ios::binary);
  for (size_t i = 0; i < ids.size(); ++i) {
    const std::string wav = make_wav({}, synthetic_rir(rng, 0.3 + 0.05 * (i % 6), length));
    std::ofstream(wavs[i], std::ios::binary).write(wav.data(), static_cast<std::streamsize>(wav.size()));
    rooms << diagnose_room_line(ids[i], i) << "\n";
    list << ids[i] << " " << wavs[i] << "\n";
  }
}

RunResult run_argv(const std::vector<std::string>& argv) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], 1);
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  close(fds[1]);
  RunResult r;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) r.output.append(buf, static_cast<size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

std::string program_path(const std::string& name) {
  // TSRIR_TEST_BIN_DIR points the tests at programs built elsewhere (e.g. another build dir).
  const char* env = std::getenv("TSRIR_TEST_BIN_DIR");
  std::string p = std::string(env && *env ? env : TSRIR_BIN_DIR) + "/" + name;
  return access(p.c_str(), X_OK) == 0 ? p : "";
}

double children_peak_rss_mb() {
  struct rusage ru {};
  getrusage(RUSAGE_CHILDREN, &ru);
  return ru.ru_maxrss / 1024.0;
}

}  // namespace robust
