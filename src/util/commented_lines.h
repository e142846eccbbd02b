#pragma once

#include <istream>
#include <string>

namespace tsrir {

// The toolkit's line-based text formats (config files, room lists, array geometry files, EQ
// models, set-up tables) share one lexical rule: '#' starts a comment that runs to the end of the
// line, and a line with nothing else but whitespace is skipped. This reader applies it in one
// place and counts lines, so every format reports errors as file:line the same way.
class CommentedLines {
 public:
  explicit CommentedLines(std::istream& in) : in_(in) {}

  // The next line that has something besides a comment and whitespace, with its comment removed
  // and surrounding whitespace trimmed; false at the end of the stream.
  bool next(std::string* line);
  // Lines read so far: after next() returned true, the 1-based number of the line it returned.
  int lines_read() const { return lines_read_; }

 private:
  std::istream& in_;
  int lines_read_ = 0;
};

}  // namespace tsrir
