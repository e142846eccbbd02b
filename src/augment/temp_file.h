// Scratch files for the streaming path (reverberate_stream.h): data too long to hold in memory
// (a copied input pipe, the unscaled reverberant signal) goes to disk instead.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace tsrir {

// A temporary file named <base>.tmp.<pid>.<n> (io/atomic_output.h's make_temp_path): registered
// so that an interrupted run's handler removes it, and removed by the destructor.
class TempFile {
 public:
  explicit TempFile(const std::string& base);
  ~TempFile();
  const std::string& path() const { return path_; }
  void append(const void* data, size_t bytes);
  void write_at(uint64_t offset, const void* data, size_t bytes);
  void read_at(uint64_t offset, void* data, size_t bytes) const;
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// Where the temporaries for writing `wx` go: next to a file output (same filesystem, and
// never a final name), else in $TMPDIR (default /tmp). `what` tells them apart.
std::string temp_base_for_output(const std::string& wx, const std::string& what);

}  // namespace tsrir
