// Kaldi text tables: one "<key> <value>" per line (value = rest of line, trimmed). Written sorted
// and unique on the key under LC_ALL=C byte order, as utils/validate_data_dir.sh requires.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace tsrir {

struct TableEntry {
  std::string key;
  std::string value;
  int line = 0;          // 1-based line in the source file (0 if made in memory)
};

struct Table {
  std::string source;    // file name for messages
  std::vector<TableEntry> entries;   // in file order

  const TableEntry* find(const std::string& key) const;  // linear in size; use index() for many
  std::map<std::string, const TableEntry*> index() const;
  std::string where(const TableEntry& e) const;  // "file:line"
};

struct TableReadOptions {
  bool allow_empty_value = false;  // e.g. text lines of silent utterances
  bool allow_duplicates = false;   // spk2utt-like inputs may not repeat keys either; default error
  bool skip_comments = false;      // '#' lines (not Kaldi standard; used for our own lists)
};

// Reads a table from a file ("-" = stdin). Errors with file:line on: a line without a value,
// duplicate keys, keys with non-printable characters, a missing file.
Table read_table(const std::string& path, const TableReadOptions& options = {});
Table parse_table(const std::string& text, const std::string& source, const TableReadOptions& options = {});

// Writes sorted (byte order) and unique; throws on duplicate keys or keys containing whitespace
// or newlines. Atomic (temp + rename).
void write_table(const std::string& path, std::vector<std::pair<std::string, std::string>> rows);

// LC_ALL=C comparison (byte order).
bool c_locale_less(const std::string& a, const std::string& b);

}  // namespace tsrir
