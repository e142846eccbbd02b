// Kaldi's own command-line syntax (util/parse-options.cc), for programs that must be drop-in
// replacements of a Kaldi binary (wav-reverberate, wav-to-duration). It implements OptionsItf, so the
// library option structs register themselves here as they do with tsrir::CommandLine, but the syntax
// is Kaldi's on purpose: only `--name=value` (a bare `--name` is `true` for booleans and an error
// otherwise, so `--name value` fails as it does in Kaldi), booleans also as t/f/1/0, options end at
// the first positional argument or at `--`, names are case-insensitive with `_` == `-`, and the
// standard options --config, --help, --print-args and --verbose exist. It uses no option library:
// wav-reverberate starts once per utterance in Kaldi's pipes, and every shared library it loads is
// paid at each start.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "util/options.h"

namespace tsrir {

class KaldiOptionParser : public OptionsItf {
 public:
  explicit KaldiOptionParser(std::string usage);

  using OptionsItf::Register;
  void RegisterSpec(OptionSpec spec) override;
  void RegisterAlias(const std::string& alias, const std::string& name) override;

  enum class Outcome { kOk, kHelp };
  // Parses argv. Returns kHelp when --help was given (the caller prints usage_text() and exits 0).
  // Throws Error ("Invalid option ...") for unknown options, a missing `=value`, or a malformed
  // value. With --print-args (default true) the command line is echoed to stderr, shell-escaped.
  Outcome parse(int argc, const char* const* argv);

  const std::vector<std::string>& positionals() const { return positionals_; }
  int verbose() const { return verbose_; }
  // Whether option `name` was set by the command line or a --config file (not left at its default).
  bool given(const std::string& name) const;
  // Usage text followed by the option table (Kaldi layout: "Options:" then "Standard options:").
  std::string usage_text() const;

  // Kaldi's Escape(): quotes a word for bash only when it contains characters outside
  // [A-Za-z0-9] and "[]~#^_-+=:.,/".
  static std::string escape_for_echo(const std::string& word);

 private:
  struct Entry {
    OptionSpec spec;
    bool standard = false;
    std::vector<std::string> aliases;
    bool cleared = false;  // a repeated option: its default list was replaced by the first value
    bool given = false;    // set by the command line or a config file
  };
  void add_entry(OptionSpec spec, bool standard);
  Entry* find(const std::string& normalized_key);
  void set_option(const std::string& key, const std::string& value, bool has_equal_sign,
                  const std::string& original);
  void read_config_file(const std::string& path);

  std::string usage_;
  std::vector<Entry> entries_;                 // in registration order (the --help order)
  std::map<std::string, size_t> index_;        // normalised name or alias -> entries_ index
  std::vector<std::string> positionals_;
  std::string config_;
  bool help_ = false;
  bool print_args_ = true;
  int verbose_ = 0;
};

// The frame of a Kaldi drop-in program: `define` registers the options; argv is parsed; --help
// prints the usage to stdout (exit 0); a positional count other than `num_positionals` prints it to
// stderr (exit 1); else `body` runs with the positionals and its result is the exit status. An
// error (Error, std::exception) is reported on stderr and exits 1, as every tsrir program does
// (Kaldi's binaries exit 255; Kaldi's scripts only test for non-zero).
int run_kaldi_program(const std::string& name, const std::string& usage, int argc, const char* const* argv,
                      size_t num_positionals, const std::function<void(KaldiOptionParser&)>& define,
                      const std::function<int(const std::vector<std::string>&)>& body);

}  // namespace tsrir
