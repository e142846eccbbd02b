// Settings files written and read through the options' own Register calls (util/settings_file.h):
// every registered type round-trips, the file's order, key style and precision are the caller's,
// excluded and renamed options, and bad files are errors that name the file and line.
#include <gtest/gtest.h>

#include "util/error.h"
#include "util/settings_file.h"

using namespace tsrir;

namespace {

enum class Mode { kFast, kExact };

struct ModelSettings {
  int width = 16;
  long long steps = 1000;
  Seed seed = 0;
  double learning_rate = 3e-5;
  float gain = 0.5f;
  bool residual = false;
  std::string name = "model a";
  std::vector<std::string> lists = {"a.scp"};
  Mode mode = Mode::kFast;
  int num_threads = 1;  // run-time, not a setting
  void Register(OptionsItf* opts) {
    opts->Register("width", &width, "width");
    opts->Register("steps", &steps, "steps");
    opts->Register("seed", &seed, "seed");
    opts->RegisterAlias("random-seed", "seed");
    opts->Register("learning-rate", &learning_rate, "rate");
    opts->Register("gain", &gain, "gain");
    opts->Register("residual", &residual, "residual");
    opts->Register("name", &name, "name");
    opts->Register("list", &lists, "lists");
    opts->RegisterEnum("mode", &mode, {{"fast", Mode::kFast}, {"exact", Mode::kExact}}, "mode");
    opts->Register("num-threads", &num_threads, "threads");
  }
};

SettingsStyle sorted_style(int digits = 17) {
  SettingsStyle s;
  s.double_digits = digits;
  return s;
}

SettingsFile file_for(ModelSettings* m, SettingsStyle style = sorted_style()) {
  SettingsFile file("toy-v1", "a toy model's settings", style);
  m->Register(&file);
  file.Exclude({"num-threads"});
  return file;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SettingsFile, TextIsSortedKeyValueLinesOfTheRegisteredOptions) {
  ModelSettings m;
  m.seed = ~Seed{0};
  m.lists = {"a.scp", "b c.scp"};
  EXPECT_EQ(file_for(&m).text(),
            "format toy-v1\n"
            "gain 0.5\n"
            "learning-rate 3.0000000000000001e-05\n"
            "list a.scp\n"
            "list b c.scp\n"
            "mode fast\n"
            "name model a\n"
            "residual false\n"
            "seed 18446744073709551615\n"
            "steps 1000\n"
            "width 16\n");
}

TEST(SettingsFile, EveryTypeRoundTrips) {
  ModelSettings written;
  written.width = 64;
  written.steps = 1LL << 40;
  written.seed = 12345678901234567890ULL;
  written.learning_rate = 1.0 / 3.0;
  written.gain = 0.1f;
  written.residual = true;
  written.name = "x;y z";
  written.lists = {"one", "two", "three"};
  written.mode = Mode::kExact;
  const std::string text = file_for(&written).text();
  ModelSettings read;
  read.lists = {"default"};
  file_for(&read).parse(text, "settings.txt");
  EXPECT_EQ(read.width, written.width);
  EXPECT_EQ(read.steps, written.steps);
  EXPECT_EQ(read.seed, written.seed);
  EXPECT_EQ(read.learning_rate, written.learning_rate);  // 17 digits: exact
  EXPECT_EQ(read.gain, written.gain);
  EXPECT_EQ(read.residual, written.residual);
  EXPECT_EQ(read.name, written.name);
  EXPECT_EQ(read.lists, written.lists);
  EXPECT_EQ(read.mode, written.mode);
  EXPECT_EQ(file_for(&read).text(), text);
}

TEST(SettingsFile, StyleGivesOrderKeysAndPrecision) {
  ModelSettings m;
  SettingsStyle style;
  style.sorted = false;
  style.underscores = true;
  style.double_digits = 6;
  SettingsFile file = file_for(&m, style);
  file.Rename("name", "model_name");
  file.Order({"width", "mode"});
  EXPECT_EQ(file.text(),
            "format toy-v1\nwidth 16\nmode fast\nsteps 1000\nseed 0\nlearning_rate 3e-05\ngain 0.5\n"
            "residual false\nmodel_name model a\nlist a.scp\n");
}

TEST(SettingsFile, MissingKeysKeepTheFieldOrAreErrors) {
  ModelSettings m;
  m.width = 99;
  file_for(&m).parse("format toy-v1\nsteps 5\n", "old.txt");
  EXPECT_EQ(m.width, 99);
  EXPECT_EQ(m.steps, 5);
  SettingsStyle strict = sorted_style();
  strict.require_all = true;
  EXPECT_EQ(error_of([&] { file_for(&m, strict).parse("format toy-v1\nsteps 5\n", "old.txt"); }),
            "old.txt: settings lack 'width'");
}

// An option added to a settings struct after files were written (here "residual", default false):
// with OmitWhenDefault it is written only when on, so the older files' bytes stay what the struct
// writes with it off, and those files read even with require_all, giving it its default.
TEST(SettingsFile, OmittedWhenDefaultKeepsOlderFilesBytesAndReadable) {
  SettingsStyle strict = sorted_style();
  strict.require_all = true;
  ModelSettings defaults;
  auto omitting = [&](ModelSettings* m) {
    SettingsFile file = file_for(m, strict);
    file.OmitWhenDefault({"residual"}, file_for(&defaults, strict).values());
    return file;
  };
  const std::string without = omitting(&defaults).text();
  EXPECT_EQ(without.find("residual"), std::string::npos);
  EXPECT_EQ(omitting(&defaults).values().count("residual"), 0u);
  // Identical to the file of a struct that lacks the option, line for line.
  std::string all_lines = file_for(&defaults, strict).text();
  const std::string residual_line = "residual false\n";
  all_lines.erase(all_lines.find(residual_line), residual_line.size());
  EXPECT_EQ(without, all_lines);

  ModelSettings on;
  on.residual = true;
  const std::string with = omitting(&on).text();  // the defaults come from their own struct
  EXPECT_NE(with.find("\nresidual true\n"), std::string::npos);

  ModelSettings read;
  SettingsFile read_file = omitting(&read);
  read_file.parse(with, "new.txt");
  EXPECT_TRUE(read.residual);
  read_file.parse(without, "old.txt");  // require_all, yet no error: the default, not the field's value
  EXPECT_FALSE(read.residual);
  EXPECT_EQ(error_of([&] { file_for(&read, strict).parse(without, "old.txt"); }),
            "old.txt: settings lack 'residual'");  // without OmitWhenDefault: an error
  EXPECT_EQ(error_of([&] { file_for(&read).OmitWhenDefault({"list"}, {}); }),
            "settings: no single-valued option 'list' to omit when default (a program bug)");
  EXPECT_EQ(error_of([&] { file_for(&read).OmitWhenDefault({"residual"}, {}); }),
            "settings: no default given for 'residual' (a program bug)");
}

TEST(SettingsFile, BadFilesNameFileAndLine) {
  ModelSettings m;
  SettingsFile file = file_for(&m);
  EXPECT_EQ(error_of([&] { file.parse("width 3\n", "s.txt"); }),
            "s.txt: not a toy model's settings (no 'format toy-v1' line)");
  EXPECT_EQ(error_of([&] { file.parse("format toy-v2\n", "s.txt"); }),
            "s.txt:1: format 'toy-v2', not toy-v1 (a toy model's settings)");
  EXPECT_EQ(error_of([&] { file.parse("format toy-v1\n# c\n\nnum-threads 2\n", "s.txt"); }),
            "s.txt:4: unknown setting 'num-threads' (a toy model's settings)");
  EXPECT_EQ(error_of([&] { file.parse("format toy-v1\nwidth 2\nwidth 3\n", "s.txt"); }), "s.txt:3: 'width' given twice");
  EXPECT_EQ(error_of([&] { file.parse("format toy-v1\nmode slow\n", "s.txt"); }),
            "s.txt:2: invalid value 'slow' for 'mode': expected one of: fast, exact");
  EXPECT_EQ(error_of([&] { file.parse("format toy-v1\nsteps 1e3\n", "s.txt"); }),
            "s.txt:2: invalid value '1e3' for 'steps': expected an integer");
}

TEST(SettingsFile, ValuesALineCannotHoldAreRefusedWhenWritten) {
  ModelSettings m;
  m.name = " padded";
  EXPECT_NE(error_of([&] { file_for(&m).text(); }).find("surrounding spaces"), std::string::npos);
  m.name = "two\nlines";
  EXPECT_NE(error_of([&] { file_for(&m).text(); }).find("line break"), std::string::npos);
}

TEST(SettingsFile, ExcludingOrRenamingAnUnknownOptionIsAProgramBug) {
  ModelSettings m;
  SettingsFile file = file_for(&m);
  EXPECT_NE(error_of([&] { file.Exclude({"no-such"}); }).find("program bug"), std::string::npos);
  EXPECT_NE(error_of([&] { file.Rename("no-such", "x"); }).find("program bug"), std::string::npos);
  EXPECT_NE(error_of([&] { file.Rename("width", "steps"); }).find("program bug"), std::string::npos);
}

TEST(SettingsFile, DifferenceListsStoredValuesThatChanged) {
  EXPECT_EQ(settings_difference({{"a", "1"}, {"b", "2"}}, {{"a", "1"}, {"b", "3"}}), " --b=2");
  EXPECT_EQ(settings_difference({{"a", "1"}}, {}), " --a=1");
  EXPECT_EQ(settings_difference({{"a", "1"}}, {{"a", "1"}, {"new", "x"}}), "");
}

}  // namespace
