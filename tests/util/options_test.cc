// OptionsItf / CommandLine / --config: typed registration, enum choices, seeds, aliases, repeated
// options, Kaldi config files with the command line overriding them, and errors that end in a hint.
#include <gtest/gtest.h>

#include "test_support.h"
#include "util/cli.h"
#include "util/config_file.h"
#include "util/error.h"

using namespace tsrir;

namespace {

enum class Shape { kShoebox, kSphere };

// A library-style option struct: it registers itself, nested parts included.
struct InnerOptions {
  double gain_db = -3.5;
  void Register(OptionsItf* opts) { opts->Register("gain-db", &gain_db, "gain (dB)"); }
};

struct ToyOptions {
  bool verbose = false;
  int count = 3;
  long long big = 0;
  Seed seed = 0;
  double rate = 0.1;
  float f = 1.5f;
  std::string name = "default";
  std::vector<std::string> tags = {"t0"};
  Shape shape = Shape::kShoebox;
  InnerOptions inner;
  void Register(OptionsItf* opts) {
    opts->Register("verbose", &verbose, "talk more");
    opts->Register("count", &count, "how many");
    opts->Register("big", &big, "a 64-bit count");
    opts->Register("seed", &seed, "random seed");
    opts->RegisterAlias("random-seed", "seed");
    opts->Register("rate", &rate, "a rate");
    opts->Register("f", &f, "a float");
    opts->Register("name", &name, "a name");
    opts->Register("tag", &tags, "a tag");
    opts->RegisterEnum("shape", &shape, {{"shoebox", Shape::kShoebox}, {"sphere", Shape::kSphere}}, "room shape");
    PrefixedOptions inner_opts("inner", opts);
    inner.Register(&inner_opts);
  }
};

using TempDir = tsrir_test::ScratchDir;

std::vector<std::string> parse(ToyOptions* o, const std::vector<std::string>& args, int min_pos = 0, int max_pos = -1) {
  CommandLine cl("toy", "toy [options] <in>\ne.g.: toy --count=2 in.scp\n");
  o->Register(&cl);
  std::vector<const char*> argv = {"toy"};
  for (const auto& a : args) argv.push_back(a.c_str());
  return cl.parse(static_cast<int>(argv.size()), argv.data(), min_pos, max_pos);
}

std::string error_of(ToyOptions* o, const std::vector<std::string>& args, int min_pos = 0, int max_pos = -1) {
  try {
    parse(o, args, min_pos, max_pos);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Options, TypedValuesFromTheCommandLine) {
  ToyOptions o;
  auto pos = parse(&o, {"--verbose", "in.scp", "--count", "7", "--big=-9000000000", "--rate=2.5e-3", "--f=0.25",
                        "--name=", "--shape=sphere", "--inner.gain-db=6", "out"});
  EXPECT_EQ(pos, (std::vector<std::string>{"in.scp", "out"}));
  EXPECT_TRUE(o.verbose);
  EXPECT_EQ(o.count, 7);
  EXPECT_EQ(o.big, -9000000000LL);
  EXPECT_DOUBLE_EQ(o.rate, 2.5e-3);
  EXPECT_FLOAT_EQ(o.f, 0.25f);
  EXPECT_EQ(o.name, "");
  EXPECT_EQ(o.shape, Shape::kSphere);
  EXPECT_DOUBLE_EQ(o.inner.gain_db, 6.0);
  for (const char* no : {"--verbose=false", "--verbose=0", "--verbose=no", "--verbose=off"}) {
    ToyOptions p;
    p.verbose = true;
    parse(&p, {no});
    EXPECT_FALSE(p.verbose) << no;
  }
}

TEST(Options, DefaultsAreTheFieldValuesAndTheLastOccurrenceWins) {
  ToyOptions o;
  parse(&o, {});
  EXPECT_EQ(o.count, 3);
  EXPECT_EQ(o.name, "default");
  EXPECT_EQ(o.tags, std::vector<std::string>{"t0"});
  parse(&o, {"--count=1", "--count=2"});
  EXPECT_EQ(o.count, 2);
}

TEST(Options, SeedsAcceptTheFullRangeAndNegativeSeedsWrapAsIntDid) {
  ToyOptions o;
  parse(&o, {"--seed=18446744073709551615"});
  EXPECT_EQ(o.seed, 18446744073709551615ULL);
  parse(&o, {"--seed=-1"});
  EXPECT_EQ(o.seed, static_cast<Seed>(static_cast<int64_t>(static_cast<int>(-1))));
  parse(&o, {"--random-seed=42"});  // the Kaldi name is an alias
  EXPECT_EQ(o.seed, 42u);
  EXPECT_NE(error_of(&o, {"--seed=1.5"}).find("expected an integer"), std::string::npos);
  EXPECT_NE(error_of(&o, {"--seed=18446744073709551616"}).find("out of range"), std::string::npos);
}

TEST(Options, RepeatedOptionsReplaceTheDefaultList) {
  ToyOptions o;
  parse(&o, {"--tag=a", "--tag", "b"});
  EXPECT_EQ(o.tags, (std::vector<std::string>{"a", "b"}));
}

TEST(Options, BadValuesNameTheOptionAndEndWithAOneLineHint) {
  ToyOptions o;
  const std::string e = error_of(&o, {"--count=abc"});
  EXPECT_NE(e.find("invalid value 'abc' for --count: expected an integer"), std::string::npos) << e;
  EXPECT_NE(e.find("Try 'toy --help'."), std::string::npos) << e;
  EXPECT_EQ(e.find("e.g.: toy"), std::string::npos) << "the whole usage is not repeated: " << e;
  EXPECT_NE(error_of(&o, {"--count=99999999999"}).find("out of range"), std::string::npos);
  EXPECT_NE(error_of(&o, {"--rate=fast"}).find("expected a number"), std::string::npos);
  EXPECT_NE(error_of(&o, {"--rate=inf"}).find("out of range"), std::string::npos);
  EXPECT_NE(error_of(&o, {"--verbose=maybe"}).find("expected true or false"), std::string::npos);
  const std::string shape = error_of(&o, {"--shape=cube"});
  EXPECT_NE(shape.find("invalid value 'cube' for --shape: expected one of: shoebox, sphere"), std::string::npos)
      << shape;
  const std::string unknown = error_of(&o, {"--nope=1"});
  EXPECT_NE(unknown.find("--nope"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("Try 'toy --help'."), std::string::npos) << unknown;
  EXPECT_NE(error_of(&o, {"--coun=1"}), "(no error)");  // no guessing of abbreviations
  const std::string arity = error_of(&o, {"a"}, 2, 2);
  EXPECT_NE(arity.find("wrong number of arguments (1; expected 2)"), std::string::npos) << arity;
  EXPECT_NE(arity.find("Try 'toy --help'."), std::string::npos) << arity;
  EXPECT_NE(error_of(&o, {"a", "b", "c"}, 1, 2), "(no error)");
}

TEST(Options, UsageShowsDefaultsChoicesAliasesAndConfig) {
  ToyOptions o;
  CommandLine cl("toy", "toy [options]\ne.g.: toy --count=2\n");
  o.Register(&cl);
  const std::string u = cl.usage_text();
  for (const char* s : {"e.g.: toy", "--count", "(=3)", "(=0.1)", "(shoebox | sphere)", "(=shoebox)",
                        "--random-seed", "same as --seed", "--config", "--inner.gain-db", "(=-3.5)", "may be repeated"}) {
    EXPECT_NE(u.find(s), std::string::npos) << s << "\n" << u;
  }
}

TEST(Options, ChoiceTablesNameValuesForEveryReader) {
  const Choices<Shape> shapes = {{"shoebox", Shape::kShoebox}, {"sphere", Shape::kSphere}};
  EXPECT_EQ(choice_value(shapes, "sphere"), Shape::kSphere);
  EXPECT_EQ(choice_name(shapes, Shape::kShoebox), "shoebox");
  EXPECT_EQ(choice_list(shapes, " | "), "shoebox | sphere");
  try {
    parse_choice(shapes, "cube", "room shape");
    FAIL() << "cube accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "unknown room shape 'cube' (expected shoebox, sphere)");
  }
  EXPECT_THROW(choice_value(shapes, "cube"), Error);
}

TEST(Options, RegisteringANameTwiceIsAProgramBug) {
  CommandLine cl("toy", "u");
  int a = 0, b = 0;
  cl.Register("a", &a, "");
  EXPECT_THROW(cl.Register("a", &b, ""), Error);
  EXPECT_THROW(cl.Register("config", &b, ""), Error);
  EXPECT_THROW(cl.RegisterAlias("b", "missing"), Error);
}

TEST(ConfigFile, KaldiFormatWithCommentsBlankLinesAndCommandLineOverride) {
  TempDir dir;
  const std::string conf = dir.write("toy.conf",
                                     "# settings of the toy\n"
                                     "\n"
                                     "--count=5   # trailing comment\n"
                                     "  --rate=0.5\r\n"
                                     "--verbose\n"
                                     "--shape=sphere\n"
                                     "--random-seed=7\n"
                                     "--tag=c1\n"
                                     "--tag=c2\n"
                                     "--inner.gain-db=-1\n");
  ToyOptions o;
  auto pos = parse(&o, {"--count=9", "in", "--config=" + conf});
  EXPECT_EQ(pos, std::vector<std::string>{"in"});
  EXPECT_EQ(o.count, 9);  // the command line overrides the file, wherever --config stands
  EXPECT_DOUBLE_EQ(o.rate, 0.5);
  EXPECT_TRUE(o.verbose);
  EXPECT_EQ(o.shape, Shape::kSphere);
  EXPECT_EQ(o.seed, 7u);
  EXPECT_EQ(o.tags, (std::vector<std::string>{"c1", "c2"}));
  EXPECT_DOUBLE_EQ(o.inner.gain_db, -1.0);
  ToyOptions p;
  parse(&p, {"--config", conf, "--tag=cli", "--verbose=false"});
  EXPECT_EQ(p.tags, std::vector<std::string>{"cli"});  // a repeated option is replaced, not appended to
  EXPECT_FALSE(p.verbose);
}

TEST(ConfigFile, ErrorsNameFileAndLine) {
  TempDir dir;
  ToyOptions o;
  const std::string bad_line = dir.write("a.conf", "# c\n--count=1\ncount=2\n");
  EXPECT_NE(error_of(&o, {"--config=" + bad_line}).find(bad_line + ":3: expected --name=value"), std::string::npos);
  const std::string unknown = dir.write("b.conf", "\n--nope=1\n");
  const std::string e = error_of(&o, {"--config=" + unknown});
  EXPECT_NE(e.find(unknown + ":2: unknown option '--nope'"), std::string::npos) << e;
  EXPECT_NE(e.find("Try 'toy --help'."), std::string::npos) << e;
  const std::string bad_value = dir.write("c.conf", "--rate=x\n");
  EXPECT_NE(error_of(&o, {"--config=" + bad_value}).find(bad_value + ":1: invalid value 'x' for --rate"),
            std::string::npos);
  const std::string no_value = dir.write("d.conf", "--count\n");
  EXPECT_NE(error_of(&o, {"--config=" + no_value}).find(no_value + ":1: option --count needs a value"),
            std::string::npos);
  const std::string nested = dir.write("e.conf", "--config=a.conf\n");
  EXPECT_NE(error_of(&o, {"--config=" + nested}).find(nested + ":1: --config cannot be nested"), std::string::npos);
  EXPECT_NE(error_of(&o, {"--config=" + dir.write("", "") + "/missing.conf"}).find("cannot read config file"),
            std::string::npos);
}

TEST(ConfigFile, ReadsEntriesWithLines) {
  TempDir dir;
  const auto entries = read_config_file(dir.write("x.conf", "--a=1 # c\n\n# only a comment\n--b\n--c = x y \n"));
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].name, "a");
  EXPECT_EQ(entries[0].value, "1");
  EXPECT_EQ(entries[0].line, 1);
  EXPECT_FALSE(entries[1].has_value);
  EXPECT_EQ(entries[1].line, 4);
  EXPECT_EQ(entries[2].name, "c");
  EXPECT_EQ(entries[2].value, "x y");
}
