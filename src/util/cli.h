// Kaldi-style command lines: `--name=value` and `--name value`, unknown options are errors,
// `--help` prints the usage (which must contain an example) and exits 0, and every program takes
// `--config=FILE` (Kaldi's config format, util/config_file.h; the command line overrides the file).
// CommandLine implements OptionsItf (util/options.h), so library option structs register themselves:
//   CommandLine cli("rir-metrics", usage);
//   MetricsOptions opts;  opts.Register(&cli);
//   std::vector<std::string> args = cli.parse(argc, argv, 1, -1);
// Errors (unknown option, bad value, wrong number of arguments) are an Error whose message ends
// with the one-line hint "Try '<program> --help'." rather than the whole usage.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "util/log.h"
#include "util/options.h"
#include "util/program.h"

namespace tsrir {

class CommandLine : public OptionsItf {
 public:
  // `usage` is printed by --help: what the program does, its synopsis and at least one example line.
  CommandLine(std::string program, std::string usage);
  ~CommandLine() override;

  using OptionsItf::Register;
  void RegisterSpec(OptionSpec spec) override;
  void RegisterAlias(const std::string& alias, const std::string& name) override;

  // The earlier names of Register, kept for programs not yet converted.
  template <typename T>
  void option(const std::string& name, T* value, const std::string& help) {
    Register(name, value, help);
  }
  void flag(const std::string& name, bool* value, const std::string& help) { Register(name, value, help); }
  void multi_option(const std::string& name, std::vector<std::string>* values, const std::string& help) {
    Register(name, values, help);
  }

  // Boolean options then also take their value as the next word, "--shift-output true|false" (the
  // syntax of Kaldi's Python scripts, e.g. reverberate_data_dir.py); otherwise that word would be a
  // positional argument.
  void accept_separate_boolean_values() { separate_boolean_values_ = true; }

  // Parses argv (after the --config files); returns the positional arguments. Exits 0 after printing
  // the usage for --help (or -h); throws Error for unknown options, bad values, unreadable or malformed
  // config files (naming file:line), or a positional count outside [min, max] (max < 0 = unbounded).
  std::vector<std::string> parse(int argc, const char* const* argv, int min_positional, int max_positional);

  std::string usage_text() const;
  const std::string& program() const { return program_; }
  // The one-line hint that ends every usage error: "Try '<program> --help'."
  std::string hint() const;

 private:
  const OptionSpec* find(const std::string& name) const;
  void apply(const OptionSpec& spec, const std::string& value, bool has_value, const std::string& where);

  std::string program_;
  std::string usage_;
  std::vector<OptionSpec> specs_;
  std::map<std::string, size_t> index_;          // option name or alias -> specs_ index
  std::vector<std::pair<std::string, std::string>> aliases_;  // (alias, name), in registration order
  bool separate_boolean_values_ = false;
};

}  // namespace tsrir
