// Options that register themselves, after Kaldi's OptionsItf: a library option struct declares its
// command-line names, defaults (the current field values) and help once, in
//   void Register(OptionsItf* opts) { opts->Register("num-threads", &num_threads, "..."); }
// and composite structs call their members' Register (nested). A program builds a CommandLine
// (util/cli.h, which implements OptionsItf), calls the structs' Register, parses, and reads the fields.
// Every program therefore also takes --config=FILE (Kaldi's config format, see util/config_file.h).
#pragma once
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace tsrir {

// The one seed type of the toolkit: random streams are derived from (seed, item key) by util/rng.h.
// On the command line a seed is any integer in [-2^63, 2^64); a negative one wraps (two's
// complement), so a seed that used to be parsed as `int` keeps its random stream.
using Seed = std::uint64_t;

// One option as a parser sees it; OptionsItf's typed Register calls build these.
struct OptionSpec {
  std::string name;          // without the leading "--"
  std::string help;
  std::string default_text;  // shown by --help ("" = none shown)
  bool is_flag = false;      // `--name` alone means `--name=true`
  bool repeated = false;     // each occurrence appends; see CommandLine for config-file overriding
  // Parses and stores one value; throws Error with a message that says what was expected.
  std::function<void(const std::string&)> set;
  // Repeated options only: forgets the values stored so far.
  std::function<void()> clear;
  // The current value as text that `set` reads back (a settings file, util/settings_file.h writes
  // it); floating-point values with `digits` significant digits. Repeated options: one text per
  // value. Empty for a spec made by hand without it: such an option cannot be a setting.
  std::function<std::vector<std::string>(int digits)> get;
};

class OptionsItf {
 public:
  virtual ~OptionsItf() = default;

  // `--name`, `--name=true|false` (also 1/0, yes/no, on/off).
  void Register(const std::string& name, bool* value, const std::string& help);
  void Register(const std::string& name, int* value, const std::string& help);
  void Register(const std::string& name, long* value, const std::string& help);       // std::int64_t
  void Register(const std::string& name, long long* value, const std::string& help);
  void Register(const std::string& name, unsigned* value, const std::string& help);
  // std::uint64_t = Seed: accepts negative values (two's complement), see Seed above.
  void Register(const std::string& name, unsigned long* value, const std::string& help);
  void Register(const std::string& name, float* value, const std::string& help);
  // Doubles show their default as a person writes it ("0.1", not "0.10000000000000001").
  void Register(const std::string& name, double* value, const std::string& help);
  void Register(const std::string& name, std::string* value, const std::string& help);
  // A string option that may be given several times; each occurrence appends one value.
  void Register(const std::string& name, std::vector<std::string>* values, const std::string& help);

  // A typed choice: RegisterEnum("definition", &definition, {{"iso", Def::kIso}, {"irstats", Def::kIrStats}},
  // "..."). Any other value is an error that lists the choices; --help shows them and the default.
  template <typename E>
  void RegisterEnum(const std::string& name, E* value, std::initializer_list<std::pair<const char*, E>> choices,
                    const std::string& help) {
    std::vector<std::pair<std::string, E>> table(choices.begin(), choices.end());
    std::vector<std::string> names;
    std::string default_text;
    for (const auto& c : table) {
      names.push_back(c.first);
      if (c.second == *value) default_text = c.first;
    }
    OptionSpec spec;
    spec.name = name;
    spec.help = help + " (" + join_choices(names, " | ") + ")";
    spec.default_text = default_text;
    spec.get = [table, value](int) {
      for (const auto& c : table) {
        if (c.second == *value) return std::vector<std::string>{c.first};
      }
      return std::vector<std::string>{};
    };
    spec.set = [table, names, name, value](const std::string& text) {
      for (const auto& c : table) {
        if (c.first == text) {
          *value = c.second;
          return;
        }
      }
      throw_bad_choice(name, text, names);
    };
    RegisterSpec(std::move(spec));
  }

  // Another name for an already registered option (e.g. Kaldi's --random-seed for --seed). Both
  // names are accepted; --help lists the alias next to the option.
  virtual void RegisterAlias(const std::string& alias, const std::string& name) = 0;

  // The one entry point an implementation provides; the typed Register calls above end here.
  virtual void RegisterSpec(OptionSpec spec) = 0;

 private:
  static std::string join_choices(const std::vector<std::string>& names, const std::string& sep);
  [[noreturn]] static void throw_bad_choice(const std::string& name, const std::string& text,
                                            const std::vector<std::string>& names);
};

// Registers options under a common prefix: PrefixedOptions p("eq", opts); x.Register(&p) makes
// x's "taps" appear as "--eq.taps" (Kaldi's ParseOptions(prefix, other)), for composite programs
// whose parts would otherwise register the same name.
class PrefixedOptions : public OptionsItf {
 public:
  PrefixedOptions(std::string prefix, OptionsItf* other) : prefix_(std::move(prefix)), other_(other) {}
  void RegisterAlias(const std::string& alias, const std::string& name) override {
    other_->RegisterAlias(prefix_ + "." + alias, prefix_ + "." + name);
  }
  void RegisterSpec(OptionSpec spec) override {
    spec.name = prefix_ + "." + spec.name;
    other_->RegisterSpec(std::move(spec));
  }

 private:
  std::string prefix_;
  OptionsItf* other_;
};

}  // namespace tsrir
