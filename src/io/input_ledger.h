// The inputs of a run, so that no output of the run is, contains or lies inside one of them
// (io/owned_output.h). A reader that is handed a ledger records in it what it reads (the list and
// every file the list points at); one handed none records nothing: reading has no effect on
// writing that its caller does not ask for. The run's ledger belongs to its OutputPolicy
// (run_inputs()), which every owned output and atomic file checks.
#pragma once
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace tsrir {

class InputLedger {
 public:
  // A path, a directory or an rxfilename (a pipe's existing file arguments count; Kaldi's
  // "file:offset" names its file). Resolved to real paths (through symlinks) when first checked.
  void add(const std::string& rx);
  void add(const std::vector<std::string>& rxs);
  void clear();

  // Throws Error when `output_dir` is, contains or lies inside an input.
  void check_output_dir(const std::string& output_dir);
  // Throws Error when the file `path` is an input (real paths); files inside a staging directory
  // (.tsrir-staging.tmp.*) are new by construction and not checked.
  void check_output_file(const std::string& path);

 private:
  struct Resolved {
    std::string shown;  // as the user gave it
    std::string real;   // real path
    bool is_dir = false;
  };
  void resolve_pending();  // mutex_ held
  void resolve_rx(const std::string& rx);
  void resolve_path(const std::string& path);
  std::string real_parent_of(const std::string& path);

  std::mutex mutex_;
  std::vector<std::string> pending_;
  std::vector<Resolved> resolved_;
  std::set<std::string> seen_;
  std::map<std::string, std::string> real_parent_;  // parent dir -> its real path
};

}  // namespace tsrir
