#include "util/cleanup.h"

#include <ftw.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <mutex>

namespace tsrir {
namespace {

// A fixed table of C strings so the signal handler never allocates.
constexpr int kMaxTemps = 256;
constexpr int kMaxPath = 4096;
char g_paths[kMaxTemps][kMaxPath];
volatile bool g_used[kMaxTemps];
std::mutex g_mutex;

int remove_entry(const char* path, const struct stat*, int, struct FTW*) {
  ::remove(path);
  return 0;
}

}  // namespace

void register_temp_path(const std::string& path) {
  if (path.size() >= kMaxPath) return;
  std::lock_guard<std::mutex> lock(g_mutex);
  for (int i = 0; i < kMaxTemps; ++i) {
    if (!g_used[i]) {
      std::memcpy(g_paths[i], path.c_str(), path.size() + 1);
      g_used[i] = true;
      return;
    }
  }
}

void unregister_temp_path(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_mutex);
  for (int i = 0; i < kMaxTemps; ++i) {
    if (g_used[i] && path == g_paths[i]) {
      g_used[i] = false;
      return;
    }
  }
}

void remove_registered_temps_on_signal() {
  for (int i = 0; i < kMaxTemps; ++i) {
    if (g_used[i]) {
      // Depth-first so directories are empty when removed.
      nftw(g_paths[i], remove_entry, 16, FTW_DEPTH | FTW_PHYS);
      ::remove(g_paths[i]);
      g_used[i] = false;
    }
  }
}

}  // namespace tsrir
