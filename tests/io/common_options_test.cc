// The options programs share (io/common_options.h) and the output policy a program installs
// (io/owned_output.h): one name, alias, check and help for each, whichever program binds it.
#include <gtest/gtest.h>

#include "io/common_options.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/error.h"

using namespace tsrir;

namespace {

struct Bound {
  int num_threads = 1;
  Seed seed = 0;
  SampleFormat format = SampleFormat::kInt16;
  OutputPolicy policy{"prog sub"};
};

std::string parse(Bound* b, std::vector<std::string> args) {
  CommandLine cli("prog sub", "prog sub [options]\ne.g.: prog sub --num-threads=2\n");
  CommonOptions(&cli).threads(&b->num_threads, "items run in parallel").seed(&b->seed, "the draws").audio_format(&b->format);
  b->policy.Register(&cli);
  std::vector<const char*> argv = {"prog"};
  for (const auto& a : args) argv.push_back(a.c_str());
  try {
    cli.parse(static_cast<int>(argv.size()), argv.data(), 0, 0);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CommonOptions, OneNameAliasAndCheckEach) {
  Bound b;
  EXPECT_EQ(parse(&b, {"--num-threads=3", "--random-seed=-1", "--format=float", "--overwrite"}), "");
  EXPECT_EQ(b.num_threads, 3);
  EXPECT_EQ(b.seed, ~Seed{0});
  EXPECT_EQ(b.format, SampleFormat::kFloat32);
  EXPECT_TRUE(b.policy.overwrite);
  Bound c;
  EXPECT_EQ(parse(&c, {"--seed=7"}), "");
  EXPECT_EQ(c.seed, 7u);
  EXPECT_FALSE(c.policy.overwrite);
  EXPECT_NE(parse(&c, {"--num-threads=0"}).find("invalid value '0' for --num-threads: expected at least 1"),
            std::string::npos);
  EXPECT_NE(parse(&c, {"--format=pcm"}).find("expected one of: int16, float"), std::string::npos);
}

TEST(CommonOptions, HelpSaysWhatEachProgramUsesItFor) {
  Bound b;
  CommandLine cli("prog", "prog\ne.g.: prog\n");
  CommonOptions(&cli).threads(&b.num_threads, "items run in parallel").seed(&b.seed, "the draws");
  const std::string usage = cli.usage_text();
  EXPECT_NE(usage.find("threads, at least 1 (items run in"), std::string::npos) << usage;
  EXPECT_NE(usage.find("random seed (any integer) of the draws"), std::string::npos) << usage;
  EXPECT_NE(usage.find("--random-seed"), std::string::npos) << usage;
}

TEST(OutputPolicy, IsThePrograms_NotItsSubCommands_AndInstalledExplicitly) {
  EXPECT_EQ(OutputPolicy("rir-eq apply").program, "rir-eq");
  const OutputPolicy before = output_policy();
  OutputPolicy p("prog");
  p.overwrite = true;
  install_output_policy(p);
  EXPECT_EQ(output_policy().program, "prog");
  EXPECT_TRUE(output_policy().overwrite);
  install_output_policy(before);
}

}  // namespace
