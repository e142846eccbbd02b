#include "io/kaldi_table.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "io/atomic_output.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

bool c_locale_less(const std::string& a, const std::string& b) {
  return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) {
    return static_cast<unsigned char>(x) < static_cast<unsigned char>(y);
  });
}

const TableEntry* Table::find(const std::string& key) const {
  for (const auto& e : entries)
    if (e.key == key) return &e;
  return nullptr;
}

std::map<std::string, const TableEntry*> Table::index() const {
  std::map<std::string, const TableEntry*> m;
  for (const auto& e : entries) m.emplace(e.key, &e);
  return m;
}

std::string Table::where(const TableEntry& e) const { return located(source, e.line, ""); }

Table parse_table(const std::string& text, const std::string& source, const TableReadOptions& options) {
  Table t;
  t.source = source;
  std::set<std::string> seen;
  std::istringstream in(text);
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::string stripped = trim(line);
    if (stripped.empty()) continue;
    if (options.skip_comments && stripped[0] == '#') continue;
    for (unsigned char c : stripped) {
      if (c < 0x20 && c != '\t') throw Error(located(source, line_no, "control character in line"));
    }
    size_t sp = stripped.find_first_of(" \t");
    TableEntry e;
    e.line = line_no;
    e.key = stripped.substr(0, sp);
    e.value = sp == std::string::npos ? "" : trim(stripped.substr(sp));
    if (e.value.empty() && !options.allow_empty_value) {
      throw Error(located(source, line_no, "malformed line (expected '<key> <value>'): '" + stripped + "'"));
    }
    if (!options.allow_duplicates && !seen.insert(e.key).second) {
      throw Error(located(source, line_no, "duplicate key '" + e.key + "'"));
    }
    t.entries.push_back(std::move(e));
  }
  return t;
}

Table read_table(const std::string& path, const TableReadOptions& options) {
  std::stringstream buf;
  if (path == "-") {
    buf << std::cin.rdbuf();
  } else {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open");
    buf << in.rdbuf();
  }
  return parse_table(buf.str(), path == "-" ? "<stdin>" : path, options);
}

void write_table(const std::string& path, std::vector<std::pair<std::string, std::string>> rows) {
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return c_locale_less(a.first, b.first); });
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& k = rows[i].first;
    if (k.empty() || k.find_first_of(" \t\r\n") != std::string::npos) {
      throw Error(path + ": invalid key '" + k + "' (empty or contains whitespace)");
    }
    if (rows[i].second.find('\n') != std::string::npos) throw Error(path + ": value for '" + k + "' contains a newline");
    if (i > 0 && rows[i - 1].first == k) throw Error(path + ": duplicate key '" + k + "'");
  }
  AtomicTextFile out(path);
  for (const auto& [k, v] : rows) {
    out.stream() << k;
    if (!v.empty()) out.stream() << ' ' << v;
    out.stream() << '\n';
  }
  out.commit();
}

}  // namespace tsrir
