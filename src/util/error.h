// The toolkit's one exception type. Programs catch it in run_program() and exit non-zero;
// messages are meant for the user, so they name the file (and line) that caused them.
#pragma once
#include <stdexcept>
#include <string>

namespace tsrir {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// "file:line: message" (line <= 0 omits the line).
std::string located(const std::string& file, int line, const std::string& message);

}  // namespace tsrir
