// Kaldi-style command lines over Boost.Program_options: `--name=value` and `--name value`,
// unknown options are errors, `--help` prints the usage (which must contain an example) and exits 0.
#pragma once
#include <boost/program_options.hpp>
#include <functional>
#include <string>
#include <vector>

namespace tsrir {

class CommandLine {
 public:
  // `usage` is printed by --help and on usage errors: what the program does, its synopsis and
  // at least one example line.
  CommandLine(std::string program, std::string usage);

  // Registers an option; the current value of *value is the default shown in --help.
  template <typename T>
  void option(const std::string& name, T* value, const std::string& help) {
    options_.add_options()(name.c_str(), boost::program_options::value<T>(value)->default_value(*value), help.c_str());
  }
  // Doubles show their default as written by a person ("0.1", not "0.10000000000000001").
  void option(const std::string& name, double* value, const std::string& help);
  // A boolean: `--name`, `--name=true|false` (also 1/0, yes/no).
  void flag(const std::string& name, bool* value, const std::string& help);
  // A string option that may be given several times (e.g. --rir-set-parameters).
  void multi_option(const std::string& name, std::vector<std::string>* values, const std::string& help);

  // Parses argv; returns the positional arguments. Exits 0 after printing usage for --help;
  // throws Error for unknown options, bad values, or a positional count outside [min, max]
  // (max < 0 = unbounded).
  std::vector<std::string> parse(int argc, const char* const* argv, int min_positional, int max_positional);

  std::string usage_text() const;
  const std::string& program() const { return program_; }

 private:
  std::string program_;
  std::string usage_;
  boost::program_options::options_description options_;
  std::vector<std::pair<std::string, bool*>> flags_;
};

// Runs a program body: Error and std::exception become "<program>: ERROR: <message>" on stderr
// and exit status 1. Also installs the SIGINT/SIGTERM handler that removes temporary outputs.
int run_program(const std::string& program, const std::function<int()>& body);

// Progress and log lines go to stderr, prefixed with the program name.
void log_info(const std::string& message);
void log_warning(const std::string& message);

}  // namespace tsrir
