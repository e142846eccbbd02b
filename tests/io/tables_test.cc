#include <gtest/gtest.h>

#include <filesystem>

#include "io/atomic_output.h"
#include "io/kaldi_table.h"
#include "io/rxfile.h"
#include "io/shell.h"
#include "test_support.h"
#include "util/error.h"

using namespace tsrir;
using tsrir_test::TempDirTest;

class Tables : public TempDirTest {};

TEST_F(Tables, ParsesKeyAndRestOfLine) {
  write_text("wav.scp", "u1 /a/b.wav\nu2   sox x.wav -t wav - |  \n\nu3\tc d\n");
  Table t = read_table(path("wav.scp"));
  ASSERT_EQ(t.entries.size(), 3u);
  EXPECT_EQ(t.entries[1].value, "sox x.wav -t wav - |");
  EXPECT_EQ(t.entries[2].line, 4);
  EXPECT_EQ(t.entries[2].value, "c d");
}

TEST_F(Tables, MalformedAndDuplicateLinesNameFileAndLine) {
  write_text("bad.scp", "u1 a.wav\nu2\n");
  try {
    read_table(path("bad.scp"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.scp:2"), std::string::npos) << e.what();
  }
  write_text("dup.scp", "u1 a.wav\nu1 b.wav\n");
  try {
    read_table(path("dup.scp"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("dup.scp:2"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("duplicate"), std::string::npos);
  }
  EXPECT_THROW(read_table(path("nonexistent")), Error);
}

TEST_F(Tables, WritesSortedInCLocaleOrder) {
  write_table(path("t"), {{"b", "2"}, {"B", "1"}, {"a-1", "x"}, {"a_1", "y"}, {"a", "z"}});
  // Byte order: uppercase before lowercase, '-' (0x2d) before '_' (0x5f).
  EXPECT_EQ(read_text("t"), "B 1\na z\na-1 x\na_1 y\nb 2\n");
  EXPECT_THROW(write_table(path("u"), {{"a", "1"}, {"a", "2"}}), Error);
  EXPECT_THROW(write_table(path("v"), {{"a b", "1"}}), Error);
  EXPECT_FALSE(std::filesystem::exists(path("u")));
}

TEST_F(Tables, ShellQuotingNeverExecutes) {
  const std::string hostile = path("a b;touch x.wav'$(touch y)`touch z`");
  EXPECT_EQ(shell_quote("plain/path-1.wav"), "plain/path-1.wav");
  std::string cmd = "printf %s " + shell_quote(hostile) + " |";
  auto out = read_rxfile(cmd);
  EXPECT_EQ(std::string(out.begin(), out.end()), hostile);
  EXPECT_FALSE(std::filesystem::exists("x.wav"));
  EXPECT_FALSE(std::filesystem::exists(path("x.wav")));
  EXPECT_FALSE(std::filesystem::exists("y"));
  EXPECT_FALSE(std::filesystem::exists("z"));
}

TEST_F(Tables, FailingPipeIsAnError) {
  try {
    read_rxfile("echo partial; echo oops >&2; exit 5 |", "wav.scp:4");
    FAIL();
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("wav.scp:4"), std::string::npos);
    EXPECT_NE(m.find("exit status 5"), std::string::npos);
    EXPECT_NE(m.find("oops"), std::string::npos);
  }
  EXPECT_THROW(read_rxfile("kill -9 $$ |"), Error);
}

TEST_F(Tables, AtomicTextFileNeverLeavesPartialOutput) {
  write_text("keep.txt", "old\n");
  {
    AtomicTextFile f(path("keep.txt"));
    f.stream() << "new, but abandoned";
  }
  EXPECT_EQ(read_text("keep.txt"), "old\n");
  {
    AtomicTextFile f(path("keep.txt"));
    f.stream() << "new\n";
    f.commit();
  }
  EXPECT_EQ(read_text("keep.txt"), "new\n");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir_)) ++files, (void)e;
  EXPECT_EQ(files, 1);
}

TEST_F(Tables, InterruptedProgramRemovesItsTemporaries) {
  // A child process writes into a temp file, then gets SIGINT: the handler installed by
  // run_program removes the temp, and the final name never appears.
  const std::string final_path = path("out.txt");
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    extern int interrupted_child(const std::string&);
    _exit(interrupted_child(final_path));
  }
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_FALSE(std::filesystem::exists(final_path));
  for (const auto& e : std::filesystem::directory_iterator(dir_)) ADD_FAILURE() << "left behind: " << e.path();
}

#include <csignal>

#include "util/cli.h"

int interrupted_child(const std::string& final_path) {
  return run_program("child", [&] {
    AtomicTextFile f(final_path);
    f.stream() << "partial" << std::flush;
    std::raise(SIGINT);
    f.commit();
    return 0;
  });
}
