#include <gtest/gtest.h>

#include "util/cli.h"
#include "util/error.h"

using namespace tsrir;

namespace {
std::vector<std::string> parse(const std::vector<std::string>& args, double* x, bool* b, std::string* s,
                               int min_pos = 0, int max_pos = -1) {
  CommandLine cl("prog", "prog [options] <a>\ne.g.: prog --x=2 a.scp\n");
  cl.option("x", x, "a number");
  cl.flag("flag", b, "a flag");
  cl.option("name", s, "a string");
  std::vector<const char*> argv = {"prog"};
  for (const auto& a : args) argv.push_back(a.c_str());
  return cl.parse(static_cast<int>(argv.size()), argv.data(), min_pos, max_pos);
}
}  // namespace

TEST(CommandLine, KaldiAndGnuStyles) {
  double x = 1;
  bool b = false;
  std::string s = "d";
  auto pos = parse({"--x=2.5", "--name", "abc", "in.scp", "--flag", "out"}, &x, &b, &s);
  EXPECT_DOUBLE_EQ(x, 2.5);
  EXPECT_EQ(s, "abc");
  EXPECT_TRUE(b);
  EXPECT_EQ(pos, (std::vector<std::string>{"in.scp", "out"}));
  b = true;
  parse({"--flag=false"}, &x, &b, &s);
  EXPECT_FALSE(b);
}

TEST(CommandLine, ErrorsOnUnknownOptionsBadValuesAndArity) {
  double x = 1;
  bool b = false;
  std::string s;
  EXPECT_THROW(parse({"--nope=1"}, &x, &b, &s), Error);
  EXPECT_THROW(parse({"--x=abc"}, &x, &b, &s), Error);
  EXPECT_THROW(parse({"--fl"}, &x, &b, &s), Error);  // no guessing of abbreviations
  EXPECT_THROW(parse({"a"}, &x, &b, &s, 2, 2), Error);
  EXPECT_THROW(parse({"a", "b", "c"}, &x, &b, &s, 1, 2), Error);
  try {
    parse({"--nope"}, &x, &b, &s);
  } catch (const Error& e) {
    // The error ends with a one-line hint, not the whole usage (which would scroll the error away).
    EXPECT_NE(std::string(e.what()).find("Try 'prog --help'."), std::string::npos);
    EXPECT_EQ(std::string(e.what()).find("e.g.: prog"), std::string::npos);
  }
}

TEST(CommandLine, RunProgramTurnsErrorsIntoExitStatus) {
  EXPECT_EQ(run_program("p", [] { return 0; }), 0);
  testing::internal::CaptureStderr();
  EXPECT_EQ(run_program("p", []() -> int { throw Error("file.scp:3: bad"); }), 1);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("p: ERROR: file.scp:3: bad"), std::string::npos);
}

// Kaldi's Python scripts write booleans as "--shift-output true": accepted when a program asks for it
// (reverberate-data); otherwise the word stays a positional argument.
TEST(CommandLine, SeparateBooleanValuesOnRequest) {
  for (bool accept : {false, true}) {
    bool b = true;
    CommandLine cl("prog", "prog [options] <a>\ne.g.: prog --flag false a\n");
    cl.flag("flag", &b, "a flag");
    if (accept) cl.accept_separate_boolean_values();
    const char* argv[] = {"prog", "--flag", "FALSE", "a"};
    const std::vector<std::string> pos = cl.parse(4, argv, 0, -1);
    if (accept) {
      EXPECT_FALSE(b);
      EXPECT_EQ(pos, (std::vector<std::string>{"a"}));
    } else {
      EXPECT_TRUE(b);
      EXPECT_EQ(pos, (std::vector<std::string>{"FALSE", "a"}));
    }
  }
}
