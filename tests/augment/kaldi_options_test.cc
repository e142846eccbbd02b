// Kaldi's option syntax, as wav-reverberate must accept and reject it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "augment/kaldi_options.h"
#include "reference_model.h"
#include "test_support.h"
#include "util/error.h"

namespace {

struct Parsed {
  bool flag = true;
  int channel = 0;
  float volume = 0;
  std::string rir;
  std::vector<std::string> positionals;
};

Parsed parse(std::vector<std::string> args) {
  Parsed p;
  tsrir::KaldiOptionParser po("usage");
  po.Register("shift-output", &p.flag, "bool");
  po.Register("input-wave-channel", &p.channel, "int");
  po.Register("volume", &p.volume, "float");
  po.Register("impulse-response", &p.rir, "string");
  args.insert(args.begin(), "prog");
  args.insert(args.begin() + 1, "--print-args=false");
  std::vector<const char*> argv;
  for (auto& a : args) argv.push_back(a.c_str());
  po.parse(static_cast<int>(argv.size()), argv.data());
  p.positionals = po.positionals();
  return p;
}

TEST(KaldiOptions, NameEqualsValue) {
  Parsed p = parse({"--impulse-response=sox r.wav -t wav - |", "--volume=0.5", "--input-wave-channel=1", "a", "b"});
  EXPECT_EQ(p.rir, "sox r.wav -t wav - |");
  EXPECT_FLOAT_EQ(p.volume, 0.5f);
  EXPECT_EQ(p.channel, 1);
  EXPECT_EQ(p.positionals, (std::vector<std::string>{"a", "b"}));
}

TEST(KaldiOptions, BooleansAndNames) {
  EXPECT_FALSE(parse({"--shift-output=false", "a", "b"}).flag);
  EXPECT_FALSE(parse({"--shift-output=FALSE", "a", "b"}).flag);
  EXPECT_TRUE(parse({"--shift-output=false", "--shift-output", "a", "b"}).flag);  // bare = true
  EXPECT_FALSE(parse({"--Shift_Output=f", "a", "b"}).flag);                       // case, '_'
  EXPECT_THROW(parse({"--shift-output=maybe", "a", "b"}), tsrir::Error);
  EXPECT_THROW(parse({"--shift-output=", "a", "b"}), tsrir::Error);
}

TEST(KaldiOptions, SpaceSeparatedValueIsRejected) {
  EXPECT_THROW(parse({"--impulse-response", "rir.wav", "a", "b"}), tsrir::Error);
  EXPECT_THROW(parse({"--volume", "2", "a", "b"}), tsrir::Error);
  // A bool then swallows nothing: "false" becomes a positional argument.
  EXPECT_EQ(parse({"--shift-output", "false", "a", "b"}).positionals.size(), 3u);
}

TEST(KaldiOptions, UnknownOptionIsAnError) {
  EXPECT_THROW(parse({"--no-such-option=1", "a", "b"}), tsrir::Error);
  EXPECT_THROW(parse({"--=1", "a", "b"}), tsrir::Error);
}

TEST(KaldiOptions, OptionsEndAtFirstPositional) {
  Parsed p = parse({"a", "b", "--volume=3"});
  EXPECT_EQ(p.positionals.size(), 3u);
  EXPECT_FLOAT_EQ(p.volume, 0.0f);
  Parsed q = parse({"--volume=3", "--", "--a", "b"});
  EXPECT_EQ(q.positionals, (std::vector<std::string>{"--a", "b"}));
  Parsed stdio = parse({"-", "-"});
  EXPECT_EQ(stdio.positionals, (std::vector<std::string>{"-", "-"}));
}

TEST(KaldiOptions, ConfigFileThenCommandLine) {
  const std::string dir = tsrir_test::make_scratch_dir("config").string();
  {
    std::ofstream f(dir + "/c.conf");
    f << "# comment\n--volume=2.5  # trailing comment\n\n--impulse-response=from_config.wav\n";
  }
  Parsed p = parse({"--config=" + dir + "/c.conf", "--impulse-response=cli.wav", "a", "b"});
  EXPECT_FLOAT_EQ(p.volume, 2.5f);
  EXPECT_EQ(p.rir, "cli.wav");
  {
    std::ofstream f(dir + "/bad.conf");
    f << "volume=2\n";
  }
  EXPECT_THROW(parse({"--config=" + dir + "/bad.conf", "a", "b"}), tsrir::Error);
  EXPECT_THROW(parse({"--config=" + dir + "/missing.conf", "a", "b"}), tsrir::Error);
  std::filesystem::remove_all(dir);
}

TEST(KaldiOptions, HelpAndEscape) {
  tsrir::KaldiOptionParser po("Usage: x\ne.g. x a b");
  float v = 0;
  po.Register("volume", &v, "gain");
  const char* argv[] = {"prog", "a", "--help"};  // --help is found anywhere among options only
  EXPECT_EQ(po.parse(3, argv), tsrir::KaldiOptionParser::Outcome::kHelp);
  EXPECT_NE(po.usage_text().find("--volume"), std::string::npos);
  EXPECT_NE(po.usage_text().find("Standard options:"), std::string::npos);
  EXPECT_EQ(tsrir::KaldiOptionParser::escape_for_echo("--snrs=1.5"), "--snrs=1.5");
  EXPECT_EQ(tsrir::KaldiOptionParser::escape_for_echo("a b"), "'a b'");
  EXPECT_EQ(tsrir::KaldiOptionParser::escape_for_echo("it's"), "\"it's\"");
  EXPECT_EQ(tsrir::KaldiOptionParser::escape_for_echo("$x'"), "'$x'\\'''");
}

}  // namespace
