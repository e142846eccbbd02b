#include "util/config_file.h"

#include "util/commented_lines.h"

#include <fstream>
#include <utility>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

std::vector<ConfigEntry> read_config_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read config file '" + path + "'");
  std::vector<ConfigEntry> entries;
  CommentedLines lines(in);
  std::string line;
  while (lines.next(&line)) {
    const int line_no = lines.lines_read();
    if (!starts_with(line, "--") || line.size() == 2 || line[2] == '=') {
      throw Error(located(path, line_no,
                          "expected --name=value (a config line of a command-line program), got '" + line + "'"));
    }
    ConfigEntry e;
    e.line = line_no;
    const size_t eq = line.find('=');
    e.name = trim(line.substr(2, eq == std::string::npos ? std::string::npos : eq - 2));
    if (eq != std::string::npos) {
      e.has_value = true;
      e.value = trim(line.substr(eq + 1));
    }
    if (e.name.find_first_of(" \t") != std::string::npos) {
      throw Error(located(path, line_no, "expected --name=value, got '" + line + "'"));
    }
    entries.push_back(std::move(e));
  }
  if (in.bad()) throw Error("error reading config file '" + path + "'");
  return entries;
}

}  // namespace tsrir
