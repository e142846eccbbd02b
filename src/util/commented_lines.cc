#include "util/commented_lines.h"

#include "util/strings.h"

namespace tsrir {

bool CommentedLines::next(std::string* line) {
  std::string raw;
  while (std::getline(in_, raw)) {
    ++lines_read_;
    const size_t hash = raw.find('#');
    if (hash != std::string::npos) raw.erase(hash);
    *line = trim(raw);
    if (!line->empty()) return true;
  }
  return false;
}

}  // namespace tsrir
