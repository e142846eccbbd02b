#include "io/atomic_output.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "io/owned_output.h"
#include "util/error.h"
#include "util/remove_tree.h"

namespace fs = std::filesystem;

namespace tsrir {

std::string make_temp_path(const std::string& final_path) {
  static std::atomic<unsigned> counter{0};
  std::string p = final_path;
  while (p.size() > 1 && p.back() == '/') p.pop_back();
  std::string temp = p + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  register_temp_path(temp);
  return temp;
}

void commit_temp_path(const std::string& temp_path, const std::string& final_path) {
  std::error_code ec;
  fs::rename(temp_path, final_path, ec);
  if (ec) {
    throw Error("cannot rename " + temp_path + " to " + final_path + ": " + ec.message());
  }
  unregister_temp_path(temp_path);
}

void discard_temp_path(const std::string& temp_path) {
  std::error_code ec;
  remove_tree(temp_path, ec);
  unregister_temp_path(temp_path);
}

AtomicTextFile::AtomicTextFile(const std::string& final_path) : final_path_(final_path) {
  if (final_path == "-") {
    to_stdout_ = true;
    return;
  }
  run_inputs()->check_output_file(final_path);
  temp_path_ = make_temp_path(final_path);
  file_.open(temp_path_, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!file_) {
    discard_temp_path(temp_path_);
    throw Error("cannot open " + final_path + " for writing: " + std::strerror(errno));
  }
}

AtomicTextFile::~AtomicTextFile() {
  if (!to_stdout_ && !committed_) {
    file_.close();
    discard_temp_path(temp_path_);
  }
}

std::ostream& AtomicTextFile::stream() { return to_stdout_ ? std::cout : file_; }

void AtomicTextFile::commit() {
  if (to_stdout_) {
    std::cout.flush();
    if (!std::cout) throw Error("error writing to standard output");
    committed_ = true;
    return;
  }
  file_.flush();
  if (!file_) throw Error("error writing " + final_path_);
  file_.close();
  commit_temp_path(temp_path_, final_path_);
  committed_ = true;
}

std::string absolute_path(const std::string& path) {
  if (path.empty() || path == "-") return path;
  return fs::absolute(fs::path(path)).lexically_normal().string();
}

}  // namespace tsrir
