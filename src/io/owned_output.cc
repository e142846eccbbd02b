#include "io/owned_output.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "io/atomic_output.h"
#include "io/common_options.h"
#include "util/error.h"
#include "util/log.h"
#include "util/strings.h"
#include "util/remove_tree.h"

namespace fs = std::filesystem;

namespace tsrir {

const char* const kOwnedMarkerName = ".tsrir-owned";

namespace {

const std::string kStagingPrefix = ".tsrir-staging";

// ---- the marker -----------------------------------------------------------------------------

struct MarkerEntry {
  long long size = -1;
  long long mtime_ns = -1;
  std::string program, owner;  // owner "-" = the directory itself
};
using Marker = std::map<std::string, MarkerEntry>;  // file name -> entry

std::string marker_path(const std::string& dir) { return (fs::path(dir) / kOwnedMarkerName).string(); }

bool read_marker(const std::string& dir, Marker* marker) {
  const std::string path = marker_path(dir);
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, '\t')) f.push_back(field);
    if (f.size() != 5) throw Error(path + ":" + std::to_string(line_number) + ": malformed line (5 tab-separated fields expected)");
    MarkerEntry e;
    try {
      e.size = std::stoll(f[1]);
      e.mtime_ns = std::stoll(f[2]);
    } catch (...) {
      throw Error(path + ":" + std::to_string(line_number) + ": malformed size or time");
    }
    e.program = f[3];
    e.owner = f[4];
    (*marker)[f[0]] = e;
  }
  return true;
}

void write_marker(const std::string& dir, const Marker& marker) {
  AtomicTextFile out(marker_path(dir));
  std::ostream& o = out.stream();
  o << "# Files written into this directory by tsrir programs. A tsrir program creates, replaces or\n"
       "# removes only the files listed here as its own; nothing else here is touched. Re-running the\n"
       "# same command replaces its own files; a different output needs --overwrite (docs/robustness.md).\n"
       "# <file>\t<size>\t<mtime_ns>\t<program>\t<output it belongs to ('-' = this directory)>\n";
  for (const auto& [name, e] : marker)
    o << name << '\t' << e.size << '\t' << e.mtime_ns << '\t' << e.program << '\t' << e.owner << '\n';
  out.commit();
}

bool stat_file(const std::string& path, long long* size, long long* mtime_ns) {
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) return false;
  *size = static_cast<long long>(st.st_size);
  *mtime_ns = static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  return true;
}

// An exclusive lock on a directory for as long as this lives (two runs sharing it take turns).
class DirLock {
 public:
  explicit DirLock(const std::string& dir) {
    fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) throw Error("cannot open directory " + dir + ": " + std::strerror(errno));
    while (::flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) {
        ::close(fd_);
        throw Error("cannot lock directory " + dir + ": " + std::strerror(errno));
      }
    }
  }
  ~DirLock() {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_ = -1;
};

bool is_staging_name(const std::string& name) { return name.rfind(kStagingPrefix + ".tmp.", 0) == 0; }
bool is_marker_temp(const std::string& name) { return name.rfind(std::string(kOwnedMarkerName) + ".tmp.", 0) == 0; }

// Staging directories of runs that were killed (SIGKILL): ours by name; removed when their process
// is gone.
void remove_dead_staging(const std::string& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!is_staging_name(name) && !is_marker_temp(name)) continue;
    const size_t start = name.find(".tmp.") + 5;
    const long pid = std::strtol(name.c_str() + start, nullptr, 10);
    if (pid > 0 && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      remove_tree(e.path().string(), ec);
    }
  }
}

std::string way_out(const std::string& dir) {
  return "choose a new or empty directory, or pass --overwrite to write into " + dir +
         " anyway (only files of the names this program writes are replaced; nothing else is touched)";
}

// The checks every claim makes: an input, a file in the way, a directory that is not ours.
void check_claim(const std::string& dir) {
  run_inputs()->check_output_dir(dir);
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) return;
  if (!fs::is_directory(st)) throw Error("output directory " + dir + " exists and is not a directory");
  remove_dead_staging(dir);
  if (fs::exists(marker_path(dir))) return;
  std::vector<std::string> others;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (is_staging_name(name) || is_marker_temp(name)) continue;
    others.push_back(name);
  }
  if (!others.empty() && !output_policy().overwrite) {
    std::sort(others.begin(), others.end());
    throw Error("output directory " + dir + " is not empty (holds " + std::to_string(others.size()) + " entries, e.g. '" +
                others[0] + "') and was not written by tsrir (no " + kOwnedMarkerName + "); " + way_out(dir));
  }
}

// Creates `dir` and its missing parents; returns those it created, outermost first.
std::vector<std::string> create_dirs(const std::string& dir) {
  std::vector<std::string> missing;
  fs::path p = fs::absolute(dir).lexically_normal();
  std::error_code ec;
  while (!p.empty() && !fs::exists(p, ec)) {
    missing.push_back(p.string());
    if (p == p.parent_path()) break;
    p = p.parent_path();
  }
  std::reverse(missing.begin(), missing.end());
  std::vector<std::string> created;
  for (const std::string& m : missing) {
    if (fs::create_directory(m, ec)) created.push_back(m);
    if (ec) throw Error("cannot create directory " + m + ": " + ec.message());
  }
  if (!fs::is_directory(dir)) throw Error("cannot create directory " + dir);
  return created;
}

std::string describe_writer(const MarkerEntry& e) {
  return e.program + (e.owner == "-" ? std::string() : " for " + e.owner);
}

// Throws when writing `name` into `dir` as (program, owner) would replace what is not ours.
void check_name(const std::string& dir, const Marker& marker, const std::string& name, const std::string& owner) {
  if (output_policy().overwrite) return;
  const std::string path = (fs::path(dir) / name).string();
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return;
  auto it = marker.find(name);
  if (it == marker.end()) {
    throw Error(path + " exists and was not written by tsrir (" + kOwnedMarkerName + " does not list it); " +
                "it is left alone: " + way_out(dir));
  }
  const MarkerEntry& e = it->second;
  if (e.program != output_policy().program || e.owner != owner) {
    throw Error(path + " was written by " + describe_writer(e) + ", not by this " + output_policy().program +
                (owner == "-" ? "" : " run for " + owner) + ": replacing it would change an output that " +
                "something else may point at; " + way_out(dir));
  }
  // Ours, but changed since it was written (edited, or replaced by the user): theirs now.
  long long size = 0, mtime = 0;
  if (e.size >= 0 && stat_file(path, &size, &mtime) && (size != e.size || mtime != e.mtime_ns)) {
    throw Error(path + " was written by " + describe_writer(e) + " but has changed since (" + kOwnedMarkerName +
                " records its size and time); it is left alone: " + way_out(dir));
  }
}

std::string owner_key(const std::string& owner) { return owner.empty() ? "-" : absolute_path(owner); }

class BlockSignals {
 public:
  BlockSignals() {
    sigset_t block;
    sigemptyset(&block);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&block, sig);
    pthread_sigmask(SIG_BLOCK, &block, &saved_);
  }
  ~BlockSignals() { pthread_sigmask(SIG_SETMASK, &saved_, nullptr); }

 private:
  sigset_t saved_;
};

}  // namespace

namespace {
OutputPolicy& installed_policy() {
  static OutputPolicy policy;
  return policy;
}
}  // namespace

OutputPolicy::OutputPolicy(const std::string& program_name) : program(program_name.substr(0, program_name.find(' '))) {}

void OutputPolicy::Register(OptionsItf* opts) { CommonOptions(opts).overwrite(&overwrite); }

const OutputPolicy& output_policy() { return installed_policy(); }

void install_output_policy(const OutputPolicy& policy) { installed_policy() = policy; }

InputLedger* run_inputs() { return installed_policy().inputs.get(); }

OwnedOutputDir::OwnedOutputDir(const std::string& final_dir, const std::string& owner)
    : final_dir_(final_dir), owner_(owner_key(owner)) {
  while (final_dir_.size() > 1 && final_dir_.back() == '/') final_dir_.pop_back();
  if (final_dir_.empty()) throw Error("empty output directory name");
  check_claim(final_dir_);
  created_dirs_ = create_dirs(final_dir_);
  staging_dir_ = make_temp_path((fs::path(final_dir_) / kStagingPrefix).string());
  std::error_code ec;
  if (!fs::create_directory(staging_dir_, ec) || ec) {
    unregister_temp_path(staging_dir_);
    throw Error("cannot create directory " + staging_dir_ + ": " + ec.message());
  }
}

OwnedOutputDir::~OwnedOutputDir() {
  if (committed_) return;
  discard_temp_path(staging_dir_);
  std::error_code ec;
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
    if (!fs::remove(*it, ec)) break;  // only empty directories go (never anything in them)
  }
}

void OwnedOutputDir::check_names(const std::vector<std::string>& names) const {
  Marker marker;
  read_marker(final_dir_, &marker);
  for (const std::string& n : names) check_name(final_dir_, marker, n, owner_);
}

void OwnedOutputDir::commit() {
  if (committed_) throw Error("output " + final_dir_ + " committed twice");
  std::vector<std::string> names;
  std::error_code ec;
  if (!fs::is_directory(staging_dir_, ec))
    throw Error("the files being written to " + final_dir_ + " vanished (" + staging_dir_ + " is gone)");
  for (const auto& e : fs::directory_iterator(staging_dir_)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") != std::string::npos) continue;  // a writer's own leftover temporary
    if (!e.is_regular_file()) throw Error("internal: " + e.path().string() + " is not a plain file");
    if (name.find_first_of("\t\n\r") != std::string::npos || name == kOwnedMarkerName)
      throw Error("cannot write a file named '" + name + "' into " + final_dir_);
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  const std::set<std::string> new_names(names.begin(), names.end());
  const std::string program = output_policy().program;

  DirLock lock(final_dir_);
  run_inputs()->check_output_dir(final_dir_);
  Marker marker;
  read_marker(final_dir_, &marker);
  for (const std::string& n : names) check_name(final_dir_, marker, n, owner_);

  BlockSignals block;  // an interrupt now would leave a half-committed set
  // The marker lists the new files before they appear, so no file of ours is ever unlisted.
  for (const std::string& n : names) marker[n] = MarkerEntry{-1, -1, program, owner_};
  write_marker(final_dir_, marker);
  for (const std::string& n : names) {
    const std::string from = (fs::path(staging_dir_) / n).string(), to = (fs::path(final_dir_) / n).string();
    fs::rename(from, to, ec);
    if (ec) throw Error("cannot rename " + from + " to " + to + ": " + ec.message());
    stat_file(to, &marker[n].size, &marker[n].mtime_ns);
  }
  // This writer's files from its previous run that it did not write again: removed when unchanged,
  // otherwise (someone edited them) left and forgotten.
  for (auto it = marker.begin(); it != marker.end();) {
    const MarkerEntry& e = it->second;
    if (new_names.count(it->first) || e.program != program || e.owner != owner_) {
      ++it;
      continue;
    }
    const std::string path = (fs::path(final_dir_) / it->first).string();
    long long size = 0, mtime = 0;
    if (stat_file(path, &size, &mtime)) {
      if (size == e.size && mtime == e.mtime_ns) {
        fs::remove(path, ec);
      } else {
        log_warning(path + " was written by an earlier run but changed since: left in place");
      }
    }
    it = marker.erase(it);
  }
  write_marker(final_dir_, marker);
  discard_temp_path(staging_dir_);
  committed_ = true;
}

void claim_output_dir(const std::string& dir, const std::vector<std::string>& names) {
  check_claim(dir);
  create_dirs(dir);
  DirLock lock(dir);
  Marker marker;
  read_marker(dir, &marker);
  for (const std::string& n : names) check_name(dir, marker, n, "-");
  bool changed = false;
  for (const std::string& n : names) {
    auto it = marker.find(n);
    if (it == marker.end() || it->second.program != output_policy().program || it->second.owner != "-") {
      marker[n] = MarkerEntry{-1, -1, output_policy().program, "-"};
      changed = true;
    }
  }
  if (changed || !fs::exists(marker_path(dir))) write_marker(dir, marker);
}

}  // namespace tsrir
