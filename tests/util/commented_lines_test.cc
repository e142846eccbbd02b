// CommentedLines: the one lexical rule of the toolkit's line formats ('#' comments, blank lines
// skipped, whitespace trimmed) and the line numbers that errors name.
#include "util/commented_lines.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace tsrir {
namespace {

std::vector<std::pair<int, std::string>> read_all(const std::string& text) {
  std::istringstream in(text);
  CommentedLines lines(in);
  std::vector<std::pair<int, std::string>> out;
  std::string line;
  while (lines.next(&line)) out.emplace_back(lines.lines_read(), line);
  return out;
}

TEST(CommentedLines, DropsCommentsAndBlankLinesAndKeepsTheLineNumbers) {
  const std::string text =
      "# a header comment\n"
      "\n"
      "  first  value \t\n"
      "second # a trailing comment\n"
      "   \t  \n"
      "#third\n"
      "fourth#x#y\n"
      "last";  // no final newline
  const std::vector<std::pair<int, std::string>> expected = {
      {3, "first  value"}, {4, "second"}, {7, "fourth"}, {8, "last"}};
  EXPECT_EQ(read_all(text), expected);
}

TEST(CommentedLines, CountsEveryLineReadAtTheEnd) {
  std::istringstream in("a\n# b\n\n");
  CommentedLines lines(in);
  std::string line;
  ASSERT_TRUE(lines.next(&line));
  EXPECT_EQ(line, "a");
  EXPECT_FALSE(lines.next(&line));
  EXPECT_EQ(lines.lines_read(), 3);  // the comment and the blank line were read too
}

TEST(CommentedLines, EmptyAndCommentOnlyStreamsHaveNoLines) {
  EXPECT_TRUE(read_all("").empty());
  EXPECT_TRUE(read_all("#\n # x\n\t\n").empty());
}

TEST(CommentedLines, WindowsLineEndsAreTrimmed) {
  const std::vector<std::pair<int, std::string>> expected = {{1, "--x=1"}, {3, "--y=2"}};
  EXPECT_EQ(read_all("--x=1\r\n\r\n--y=2 # c\r\n"), expected);
}

}  // namespace
}  // namespace tsrir
