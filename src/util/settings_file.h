// Settings files ("key value" lines, e.g. a model dir's settings.txt) written and read through the
// same Register calls as the command line (util/options.h), so a setting is declared once: its
// field, and its Register line. Adding an option to a settings struct adds it to the file.
//
//   AsrTrainOptions o;  ...
//   SettingsFile file("tsrir-asr-ctc-1", "the settings of an asr-train model", style);
//   o.Register(&file);                        // the command line's calls
//   file.Exclude({"num-threads", "epochs"});   // run-time options are not settings
//   file.text();                               // "format tsrir-asr-ctc-1\nkey value\n..."
//   file.parse(text, "model/settings.txt");    // sets o's fields; errors name file:line
//
// A file holds one line per option ("format <tag>" included), or one per value of a repeated
// option; blank lines and '#' comments are skipped. Reading refuses an unknown key, a value the
// option refuses, a second line of a key and a file without the format line (or with another
// tag). Aliases are command-line names only: a file uses the option's name, or its Rename key.
#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>

#include "util/options.h"

namespace tsrir {

// A file's lines as text: key -> value (repeated options: values joined by '\n').
using SettingsValues = std::map<std::string, std::string>;

struct SettingsStyle {
  // Lines sorted by key; otherwise in the order of Order() then registration ("format" first).
  bool sorted = true;
  // Keys are option names with '_' for '-' ("learning_rate" for --learning-rate).
  bool underscores = false;
  // Significant digits of floating-point values (17: exact; fewer keeps older files' bytes).
  int double_digits = 17;
  // Reading: a setting the file lacks is an error (else its field keeps its value, as for keys
  // added after a file was written).
  bool require_all = false;
};

class SettingsFile : public OptionsItf {
 public:
  // `format_tag` is the value of the file's "format" line; `what` names such a file in errors
  // ("the settings of an asr-train model").
  SettingsFile(std::string format_tag, std::string what, SettingsStyle style = {});

  using OptionsItf::Register;
  void RegisterSpec(OptionSpec spec) override;
  void RegisterAlias(const std::string& alias, const std::string& name) override;

  // Registered options that are not settings (what may change between runs of one model).
  void Exclude(const std::vector<std::string>& names);
  // Option `name` is stored under `key` (keys of files written before settings followed options).
  void Rename(const std::string& name, const std::string& key);
  // These options are written only when their value differs from their entry in `defaults` (the
  // values() of a file bound to default-constructed options), and a file without them gives them
  // that value, even with require_all: an option added to a settings struct then leaves the bytes
  // of files written before it, and those files still read.
  void OmitWhenDefault(const std::vector<std::string>& names, const SettingsValues& defaults);
  // Unsorted style: these keys first, in this order (the rest follow in registration order).
  void Order(const std::vector<std::string>& keys);

  // The settings' current values.
  SettingsValues values() const;
  std::string text() const;
  // Sets the fields from a file's text; `where` names it in errors ("where:line: ...").
  void parse(const std::string& text, const std::string& where);
  // Sets the fields from values (e.g. another file's parse result); errors name `where`.
  void apply(const SettingsValues& values, const std::string& where);
  // The file's lines, checked (format line, known keys, no key twice) but not applied.
  SettingsValues read(const std::string& text, const std::string& where) const;

 private:
  struct Setting {
    OptionSpec spec;
    std::string key;
    bool omit_when_default = false;
    std::string default_value;  // with omit_when_default: the value that is not written
  };
  struct Line {
    std::string key, value;
    int line = 0;
  };
  const Setting* find(const std::string& key) const;
  std::vector<const Setting*> in_file_order() const;
  std::vector<Line> lines(const std::string& text, const std::string& where) const;
  void set_value(const Setting& s, const std::string& value, const std::string& where) const;
  void check_complete(const std::set<std::string>& present, const std::string& where) const;

  std::string format_tag_, what_;
  SettingsStyle style_;
  std::vector<Setting> settings_;
  std::vector<std::string> order_;
};

// Settings that differ, as " --key=stored" for each stored key whose value `asked` lacks or
// changes (empty when equal): what a resumed run reports.
std::string settings_difference(const SettingsValues& stored, const SettingsValues& asked);

// A settings file's text (Error naming `path` when it cannot be read).
std::string read_settings_text(const std::string& path);

}  // namespace tsrir
