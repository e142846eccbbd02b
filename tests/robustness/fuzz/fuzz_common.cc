#include "fuzz_common.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace tsrir::fuzz {
namespace {
const std::string* g_scratch_dir = nullptr;
}  // namespace

std::string scratch_path(const std::string& name) {
  static const std::filesystem::path dir = [] {
    // /dev/shm keeps millions of small writes off the disk when it exists.
    std::filesystem::path base = std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
    auto d = base / ("tsrir_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    // Removed at exit through a never-destroyed copy (this static is destroyed before atexit
    // handlers registered during its own construction run).
    g_scratch_dir = new std::string(d.string());
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(*g_scratch_dir, ec);
    });
    return d;
  }();
  return (dir / name).string();
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) fail("scratch write", path);
}

}  // namespace tsrir::fuzz
