// The real-data page docs/results/r3vival.md, kept true: re-runs its one command
// (docs/results/make_r3vival_page.sh) into a scratch directory and requires the committed page
// byte for byte (the diagnosis is seeded, the page holds no timing). Skips without the data.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(R3vivalPage, RegeneratesTheCommittedPage) {
  const std::string root = TSRIR_SOURCE_DIR;
  const std::string data = root + "/../shared/data/rirs/r3vival";
  if (!std::filesystem::exists(data)) GTEST_SKIP() << data << " not found (real RIRs are read in place from ../shared/data)";
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("tsrir_r3vival_page_" + std::to_string(::getpid()));
  std::filesystem::remove_all(scratch);
  std::filesystem::create_directories(scratch);
  const std::string build = std::filesystem::path(TSRIR_BIN_DIR).parent_path().string();
  const std::string page = (scratch / "r3vival.md").string();
  const std::string command = root + "/docs/results/make_r3vival_page.sh " + build + " " + page + " " +
                              (scratch / "out").string() + " >" + (scratch / "log").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text((scratch / "log").string());
  const std::string committed = read_text(root + "/docs/results/r3vival.md");
  const std::string regenerated = read_text(page);
  EXPECT_EQ(regenerated, committed) << "docs/results/r3vival.md is stale: run docs/results/make_r3vival_page.sh build";
  std::filesystem::remove_all(scratch);
}

}  // namespace
