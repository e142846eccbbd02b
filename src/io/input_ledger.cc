#include "io/input_ledger.h"

#include <filesystem>

#include "util/error.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace tsrir {
namespace {

bool is_under(const std::string& path, const std::string& dir) {
  if (dir == "/") return path.size() > 1 && path[0] == '/';
  return path.size() > dir.size() && path.compare(0, dir.size(), dir) == 0 && path[dir.size()] == '/';
}

std::string real_output_path(const std::string& dir) {
  std::error_code ec;
  std::string real = fs::weakly_canonical(fs::absolute(dir), ec).string();
  if (ec) real = fs::absolute(dir).lexically_normal().string();
  while (real.size() > 1 && real.back() == '/') real.pop_back();
  return real;
}

}  // namespace

void InputLedger::add(const std::string& rx) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.push_back(rx);
}

void InputLedger::add(const std::vector<std::string>& rxs) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.insert(pending_.end(), rxs.begin(), rxs.end());
}

void InputLedger::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.clear();
  resolved_.clear();
  seen_.clear();
  real_parent_.clear();
}

std::string InputLedger::real_parent_of(const std::string& path) {
  const std::string parent = fs::absolute(fs::path(path)).parent_path().string();
  auto it = real_parent_.find(parent);
  if (it != real_parent_.end()) return it->second;
  std::error_code ec;
  std::string real = fs::weakly_canonical(parent, ec).string();
  if (ec) real = fs::absolute(parent).lexically_normal().string();
  real_parent_[parent] = real;
  return real;
}

// One existing path: where it is (its directory's real path + its name) and, for a symlink, what
// it points at; both must stay out of every output.
void InputLedger::resolve_path(const std::string& path) {
  std::error_code ec;
  const fs::file_status link_status = fs::symlink_status(path, ec);
  if (ec || !fs::exists(link_status)) return;
  const fs::path p(path);
  std::string name = p.filename().string();
  if (name.empty() || name == "." || name == "..") {
    const std::string real = fs::weakly_canonical(fs::absolute(p), ec).string();
    if (!ec && seen_.insert(real).second) resolved_.push_back({path, real, fs::is_directory(real)});
    return;
  }
  const std::string where = (fs::path(real_parent_of(path)) / name).string();
  const bool is_dir = fs::is_directory(path, ec);
  if (seen_.insert(where).second) resolved_.push_back({path, where, is_dir});
  if (fs::is_symlink(link_status)) {
    const std::string target = fs::canonical(path, ec).string();
    if (!ec && seen_.insert(target).second) resolved_.push_back({path, target, is_dir});
  }
}

void InputLedger::resolve_rx(const std::string& rx) {
  const std::string t = trim(rx);
  if (t.empty() || t == "-") return;
  if (t.back() != '|') {
    // Kaldi's "file:offset" and "ark:" forms name a file too.
    resolve_path(t);
    const size_t colon = t.rfind(':');
    if (colon != std::string::npos && colon > 0 && !fs::exists(t)) resolve_path(t.substr(0, colon));
    return;
  }
  // A pipe: its arguments that are existing files ("sox in.wav -t wav - |", "cat a.wav |").
  for (const std::string& token : split_whitespace(t.substr(0, t.size() - 1))) {
    if (token.empty() || token[0] == '-' || token == "|") continue;
    std::error_code ec;
    if (fs::is_regular_file(token, ec)) resolve_path(token);
  }
}

void InputLedger::resolve_pending() {
  for (const std::string& rx : pending_) resolve_rx(rx);
  pending_.clear();
}

void InputLedger::check_output_dir(const std::string& output_dir) {
  std::lock_guard<std::mutex> lock(mutex_);
  resolve_pending();
  const std::string out = real_output_path(output_dir);
  for (const Resolved& in : resolved_) {
    std::string why;
    if (in.real == out) {
      why = "is the input";
    } else if (is_under(in.real, out)) {
      why = "contains the input";
    } else if (in.is_dir && is_under(out, in.real)) {
      why = "lies inside the input directory";
    } else {
      continue;
    }
    throw Error("output directory " + output_dir + " " + why + " " + in.shown +
                (in.real != in.shown ? " (real path " + in.real + ")" : "") +
                ": a program never writes where its inputs are; choose an output directory outside every input");
  }
}

void InputLedger::check_output_file(const std::string& path) {
  if (path.empty() || path == "-" || path.find("/.tsrir-staging.tmp.") != std::string::npos) return;
  std::lock_guard<std::mutex> lock(mutex_);
  resolve_pending();
  if (seen_.empty()) return;
  std::string real = (fs::path(real_parent_of(path)) / fs::path(path).filename()).string();
  std::error_code ec;
  if (!seen_.count(real) && fs::is_symlink(fs::symlink_status(path, ec))) {
    const std::string target = fs::canonical(path, ec).string();
    if (!ec) real = target;
  }
  if (seen_.count(real)) {
    throw Error("output file " + path + " is an input of this run (real path " + real +
                "): a program never writes over its inputs; choose another output name");
  }
}

}  // namespace tsrir
