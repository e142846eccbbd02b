#include "util/remove_tree.h"

#include <ftw.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

namespace tsrir {
namespace {

thread_local int t_first_errno = 0;

int remove_entry(const char* path, const struct stat*, int type, struct FTW*) {
  const int rc = type == FTW_DP ? ::rmdir(path) : ::unlink(path);
  if (rc != 0 && errno != ENOENT && t_first_errno == 0) t_first_errno = errno;
  return 0;  // keep going: remove as much as possible
}

}  // namespace

bool remove_tree(const std::string& path, std::error_code& ec) {
  ec.clear();
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return true;
    ec = std::error_code(errno, std::generic_category());
    return false;
  }
  if (!S_ISDIR(st.st_mode)) {
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
      ec = std::error_code(errno, std::generic_category());
      return false;
    }
    return true;
  }
  t_first_errno = 0;
  // FTW_DEPTH: contents before their directory; FTW_PHYS: links are entries, never followed.
  if (::nftw(path.c_str(), remove_entry, 32, FTW_DEPTH | FTW_PHYS) != 0 && t_first_errno == 0) t_first_errno = errno;
  if (t_first_errno != 0) {
    ec = std::error_code(t_first_errno, std::generic_category());
    return false;
  }
  return true;
}

void remove_tree(const std::string& path) {
  std::error_code ec;
  if (!remove_tree(path, ec)) throw std::system_error(ec, "cannot remove " + path);
}

}  // namespace tsrir
