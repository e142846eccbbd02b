// Outputs appear under their final names only when complete: written to a temporary sibling,
// then renamed. Temporaries of an interrupted run are removed by the SIGINT/SIGTERM handler
// (see run_program) or, after SIGKILL, left under names that start with the final name and
// contain ".tmp." -- never the final name itself.
#pragma once
#include <fstream>
#include <string>

#include "util/cleanup.h"

namespace tsrir {

// A temporary path next to `final_path`, registered for removal on interruption.
std::string make_temp_path(const std::string& final_path);
// Renames temp -> final (atomic on one filesystem) and unregisters it. Throws Error on failure.
void commit_temp_path(const std::string& temp_path, const std::string& final_path);
// Removes a temp file or directory tree (best effort) and unregisters it.
void discard_temp_path(const std::string& temp_path);

// A text file written atomically. "-" writes to stdout directly.
class AtomicTextFile {
 public:
  explicit AtomicTextFile(const std::string& final_path);
  ~AtomicTextFile();  // discards unless committed
  std::ostream& stream();
  void commit();      // flush, check, rename
  AtomicTextFile(const AtomicTextFile&) = delete;
  AtomicTextFile& operator=(const AtomicTextFile&) = delete;

 private:
  std::string final_path_, temp_path_;
  std::ofstream file_;
  bool to_stdout_ = false, committed_ = false;
};

// Output directories: io/owned_output.h (OwnedOutputDir), which never replaces a whole directory.

// Absolute, normalised form of a path (no symlink resolution); used when writing paths into tables.
std::string absolute_path(const std::string& path);

}  // namespace tsrir
