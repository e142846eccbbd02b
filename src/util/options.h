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

// The names of an enum's values, in the order --help lists them: the one table a choice's names
// live in, read by RegisterEnum and by anything else that names the values.
template <typename E>
using Choices = std::vector<std::pair<std::string, E>>;

// "a | b | c" (with `sep`).
template <typename E>
std::string choice_list(const Choices<E>& choices, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < choices.size(); ++i) out += (i ? sep : "") + choices[i].first;
  return out;
}

[[noreturn]] void throw_unknown_choice(const std::string& expected);

// The value named `text`; Error "expected one of: a, b" otherwise (the caller adds which option).
template <typename E>
E choice_value(const Choices<E>& choices, const std::string& text) {
  for (const auto& c : choices) {
    if (c.first == text) return c.second;
  }
  throw_unknown_choice(choice_list(choices, ", "));
}

[[noreturn]] void throw_unknown_name(const std::string& what, const std::string& text, const std::string& expected);

// The same for readers other than a command line (Python keywords, model files), whose errors say
// what the name is of: "unknown gain method 'x' (expected octave, smooth, bin)".
template <typename E>
E parse_choice(const Choices<E>& choices, const std::string& text, const std::string& what) {
  for (const auto& c : choices) {
    if (c.first == text) return c.second;
  }
  throw_unknown_name(what, text, choice_list(choices, ", "));
}

// The name of `value` ("" for a value the table lacks).
template <typename E>
std::string choice_name(const Choices<E>& choices, E value) {
  for (const auto& c : choices) {
    if (c.second == value) return c.first;
  }
  return "";
}

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
  // "..."), or a Choices table shared with other readers of the names (Python, settings files).
  // Any other value is an error that lists the choices; --help shows them and the default.
  template <typename E>
  void RegisterEnum(const std::string& name, E* value, std::initializer_list<std::pair<const char*, E>> choices,
                    const std::string& help) {
    RegisterEnum(name, value, Choices<E>(choices.begin(), choices.end()), help);
  }
  template <typename E>
  void RegisterEnum(const std::string& name, E* value, const Choices<E>& choices, const std::string& help) {
    OptionSpec spec;
    spec.name = name;
    spec.help = help + " (" + choice_list(choices, " | ") + ")";
    spec.default_text = choice_name(choices, *value);
    spec.get = [choices, value](int) {
      const std::string text = choice_name(choices, *value);
      return text.empty() ? std::vector<std::string>{} : std::vector<std::string>{text};
    };
    spec.set = [choices, value](const std::string& text) { *value = choice_value(choices, text); };
    RegisterSpec(std::move(spec));
  }

  // Another name for an already registered option (e.g. Kaldi's --random-seed for --seed). Both
  // names are accepted; --help lists the alias next to the option.
  virtual void RegisterAlias(const std::string& alias, const std::string& name) = 0;

  // The one entry point an implementation provides; the typed Register calls above end here.
  virtual void RegisterSpec(OptionSpec spec) = 0;

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
