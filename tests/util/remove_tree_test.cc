// remove_tree (the toolkit's recursive removal, used instead of std::filesystem::remove_all where
// LibTorch programs run): whole trees go, a link is removed without following it, a missing path
// is fine, and what cannot be removed is reported.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "test_support.h"
#include "util/remove_tree.h"

namespace fs = std::filesystem;

TEST(RemoveTree, RemovesNestedTreesAndFilesButNotWhatLinksPointAt) {
  tsrir_test::ScratchDir scratch;
  const fs::path keep = scratch.dir() / "keep";
  fs::create_directories(keep);
  std::ofstream(keep / "precious.txt") << "mine";
  const fs::path tree = scratch.dir() / "tree";
  fs::create_directories(tree / "a" / "b" / "c");
  std::ofstream(tree / "a" / "b" / "c" / "f.wav") << "x";
  std::ofstream(tree / "top.txt") << "y";
  fs::create_directory_symlink(keep, tree / "a" / "link_to_keep");
  std::error_code ec;
  EXPECT_TRUE(tsrir::remove_tree(tree.string(), ec)) << ec.message();
  EXPECT_FALSE(fs::exists(tree));
  EXPECT_TRUE(fs::exists(keep / "precious.txt")) << "a link inside the tree was followed";
  const fs::path file = scratch.dir() / "single.txt";
  std::ofstream(file) << "z";
  tsrir::remove_tree(file.string());
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(tsrir::remove_tree((scratch.dir() / "never_there").string(), ec));
  EXPECT_FALSE(ec);
}

TEST(RemoveTree, ReportsWhatItCannotRemove) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may remove anything: the permission case cannot be made";
  tsrir_test::ScratchDir scratch;
  const fs::path locked = scratch.dir() / "locked";
  fs::create_directories(locked / "inner");
  std::ofstream(locked / "inner" / "f") << "x";
  ::chmod((locked / "inner").c_str(), 0500);
  std::error_code ec;
  EXPECT_FALSE(tsrir::remove_tree(locked.string(), ec));
  EXPECT_TRUE(ec);
  EXPECT_THROW(tsrir::remove_tree(locked.string()), std::system_error);
  ::chmod((locked / "inner").c_str(), 0700);
}
