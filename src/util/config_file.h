// Kaldi's config-file format, read by every program's --config=FILE (util/cli.h):
//   # a comment (from '#' to the end of the line, as in Kaldi)
//   --name=value
//   --flag            (a boolean option set to true)
// one option per line; blank lines are ignored; surrounding spaces and a trailing CR are dropped.
// The command line overrides the file. Errors name file:line.
#pragma once
#include <string>
#include <vector>

namespace tsrir {

struct ConfigEntry {
  std::string name;       // without "--"
  std::string value;      // "" when has_value is false
  bool has_value = false; // "--name=value" rather than "--name"
  int line = 0;           // 1-based, for error messages
};

// Throws Error("file:line: ...") for a line that is not `--name[=value]` and for an unreadable file.
std::vector<ConfigEntry> read_config_file(const std::string& path);

}  // namespace tsrir
