#include "augment/temp_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "io/atomic_output.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

TempFile::TempFile(const std::string& base) : path_(make_temp_path(base)) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd_ < 0) {
    const std::string reason = std::strerror(errno);
    unregister_temp_path(path_);
    throw Error("cannot create temporary file " + path_ + ": " + reason);
  }
}

TempFile::~TempFile() {
  if (fd_ >= 0) ::close(fd_);
  discard_temp_path(path_);
}

void TempFile::append(const void* data, size_t bytes) {
  write_at(size_, data, bytes);
}

void TempFile::write_at(uint64_t offset, const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pwrite(fd_, p, bytes, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error("cannot write temporary file " + path_ + ": " + std::strerror(n < 0 ? errno : ENOSPC));
    p += n;
    bytes -= static_cast<size_t>(n);
    offset += static_cast<uint64_t>(n);
  }
  if (offset > size_) size_ = offset;
}

void TempFile::read_at(uint64_t offset, void* data, size_t bytes) const {
  char* p = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pread(fd_, p, bytes, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error("cannot read temporary file " + path_ + ": " + std::strerror(errno));
    if (n == 0) throw Error("temporary file " + path_ + " is shorter than written (removed while in use?)");
    p += n;
    bytes -= static_cast<size_t>(n);
    offset += static_cast<uint64_t>(n);
  }
}

std::string temp_base_for_output(const std::string& wx, const std::string& what) {
  const std::string target = trim(wx);
  if (!target.empty() && target != "-" && !starts_with(target, "|")) return target + "." + what;
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/tsrir-" + what;
}

}  // namespace tsrir
