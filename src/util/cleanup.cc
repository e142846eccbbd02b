#include "util/cleanup.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
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

// Staging trees are a directory of files (a data dir, a wav dir); a few levels suffice, and the
// bound keeps the handler's stack use small (one dirent buffer per level).
constexpr int kMaxDepth = 8;

// Everything below runs inside a signal handler that may have interrupted malloc, so it uses only
// async-signal-safe system calls: no opendir/readdir (they allocate), no nftw, no stdio. A heap
// call here once aborted rir-simulate with "malloc assertion failure in sysmalloc" when SIGINT
// landed inside a malloc of its worker.
struct LinuxDirent64 {
  ino64_t d_ino;
  off64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[];
};

void remove_children_at(int dir_fd, int depth) {
  alignas(8) char buffer[2048];
  // Entries removed while listing may shift the directory's offsets: list again from the start
  // until a pass removes nothing.
  for (int pass = 0; pass < 64; ++pass) {
    bool removed_any = false;
    if (lseek(dir_fd, 0, SEEK_SET) < 0) return;
    for (;;) {
      const long n = syscall(SYS_getdents64, dir_fd, buffer, sizeof buffer);
      if (n <= 0) break;
      for (long offset = 0; offset < n;) {
        const auto* entry = reinterpret_cast<const LinuxDirent64*>(buffer + offset);
        offset += entry->d_reclen;
        const char* name = entry->d_name;
        if (name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0))) continue;
        if (unlinkat(dir_fd, name, 0) == 0) {
          removed_any = true;
          continue;
        }
        if ((errno == EISDIR || errno == EPERM) && depth < kMaxDepth) {
          const int child = openat(dir_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (child >= 0) {
            remove_children_at(child, depth + 1);
            close(child);
          }
          if (unlinkat(dir_fd, name, AT_REMOVEDIR) == 0) removed_any = true;
        }
      }
    }
    if (!removed_any) return;
  }
}

void remove_tree_signal_safe(const char* path) {
  if (unlink(path) == 0) return;
  const int dir = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir < 0) return;
  remove_children_at(dir, 0);
  close(dir);
  rmdir(path);
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
      remove_tree_signal_safe(g_paths[i]);
      g_used[i] = false;
    }
  }
}

}  // namespace tsrir
