#include "io/shell.h"

namespace tsrir {

std::string shell_quote(const std::string& word) {
  if (word.empty()) return "''";
  bool safe = true;
  for (unsigned char c : word) {
    if (!(std::isalnum(c) || c == '_' || c == '.' || c == '/' || c == ':' || c == '=' || c == '@' ||
          c == '%' || c == '+' || c == ',' || c == '-')) {
      safe = false;
      break;
    }
  }
  if (safe) return word;
  std::string out = "'";
  for (char c : word) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  out += "'";
  return out;
}

}  // namespace tsrir
