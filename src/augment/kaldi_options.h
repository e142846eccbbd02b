// Kaldi's own command-line syntax (util/parse-options.cc), for programs that must be drop-in
// replacements of a Kaldi binary (wav-reverberate). It differs from tsrir::CommandLine on purpose:
// only `--name=value` (a bare `--name` is `true` for booleans and an error otherwise, so
// `--name value` fails as it does in Kaldi), options end at the first positional argument or at
// `--`, names are case-insensitive with `_` == `-`, and the standard options --config, --help,
// --print-args and --verbose exist.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace tsrir {

class KaldiOptionParser {
 public:
  explicit KaldiOptionParser(std::string usage);

  void add(const std::string& name, bool* value, const std::string& help);
  void add(const std::string& name, int* value, const std::string& help);
  void add(const std::string& name, float* value, const std::string& help);
  void add(const std::string& name, double* value, const std::string& help);
  void add(const std::string& name, std::string* value, const std::string& help);

  enum class Outcome { kOk, kHelp };
  // Parses argv. Returns kHelp when --help was given (the caller prints usage_text() and exits 0).
  // Throws Error ("Invalid option ...") for unknown options, a missing `=value`, or a malformed
  // value. With --print-args (default true) the command line is echoed to stderr, shell-escaped.
  Outcome parse(int argc, const char* const* argv);

  const std::vector<std::string>& positionals() const { return positionals_; }
  int verbose() const { return verbose_; }
  // Usage text followed by the option table (Kaldi layout: "Options:" then "Standard options:").
  std::string usage_text() const;

  // Kaldi's Escape(): quotes a word for bash only when it contains characters outside
  // [A-Za-z0-9] and "[]~#^_-+=:.,/".
  static std::string escape_for_echo(const std::string& word);

 private:
  enum class Kind { kBool, kInt, kFloat, kDouble, kString };
  struct Entry {
    std::string name;
    Kind kind;
    void* target;
    std::string help;
    std::string default_text;
    bool standard;
  };
  void add_entry(const std::string& name, Kind kind, void* target, const std::string& help,
                 const std::string& default_text, bool standard);
  void set_option(const std::string& key, const std::string& value, bool has_equal_sign,
                  const std::string& original);
  void read_config_file(const std::string& path);

  std::string usage_;
  std::map<std::string, Entry> entries_;  // by normalised name
  std::vector<std::string> positionals_;
  std::string config_;
  bool help_ = false;
  bool print_args_ = true;
  int verbose_ = 0;
};

// The frame of a Kaldi drop-in program: `define` registers the options; argv is parsed; --help
// prints the usage to stdout (exit 0); a positional count other than `num_positionals` prints it to
// stderr (exit 1); else `body` runs with the positionals and its result is the exit status. An
// error (Error, std::exception) is reported on stderr and exits 255, as Kaldi's binaries (-1) do.
int run_kaldi_program(const std::string& name, const std::string& usage, int argc, const char* const* argv,
                      size_t num_positionals, const std::function<void(KaldiOptionParser&)>& define,
                      const std::function<int(const std::vector<std::string>&)>& body);

}  // namespace tsrir
