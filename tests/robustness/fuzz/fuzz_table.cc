// Kaldi text tables (wav.scp, utt2spk, text, ...): parse_table on arbitrary text. The first byte
// picks the read options. Invariants: keys are non-empty words without whitespace or control
// characters, values are trimmed, line numbers rise, and a parsed table written the way
// write_table writes it parses back to the same entries.
#include <set>
#include <sstream>

#include "fuzz_common.h"
#include "io/kaldi_table.h"
#include "util/strings.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  TableReadOptions o;
  o.allow_empty_value = data[0] & 1;
  o.allow_duplicates = data[0] & 2;
  o.skip_comments = data[0] & 4;
  const std::string text = fuzz::as_text(data + 1, size - 1);
  fuzz::expect_only_errors([&] {
    Table t = parse_table(text, "fuzz.scp", o);
    std::set<std::string> keys;
    int last_line = 0;
    for (const auto& e : t.entries) {
      FUZZ_CHECK(!e.key.empty(), "empty key at line " + std::to_string(e.line));
      for (unsigned char c : e.key) FUZZ_CHECK(c > 0x20, "whitespace/control in key '" + e.key + "'");
      FUZZ_CHECK(e.value == trim(e.value), "untrimmed value '" + e.value + "'");
      FUZZ_CHECK(e.line > last_line, "line numbers must rise");
      last_line = e.line;
      if (!o.allow_empty_value) FUZZ_CHECK(!e.value.empty(), "empty value accepted");
      if (!o.allow_duplicates) FUZZ_CHECK(keys.insert(e.key).second, "duplicate key accepted: " + e.key);
      if (o.skip_comments) FUZZ_CHECK(e.key[0] != '#', "comment line read as an entry");
    }
    // Written back (one "<key> <value>" per line, as write_table does) and re-read: the same.
    std::ostringstream out;
    for (const auto& e : t.entries) out << e.key << (e.value.empty() ? "" : " ") << e.value << '\n';
    Table again = parse_table(out.str(), "again.scp", o);
    FUZZ_CHECK(again.entries.size() == t.entries.size(), "round trip changed the entry count");
    for (size_t i = 0; i < t.entries.size(); ++i) {
      FUZZ_CHECK(again.entries[i].key == t.entries[i].key, "round trip changed key " + t.entries[i].key);
      FUZZ_CHECK(again.entries[i].value == t.entries[i].value, "round trip changed value of " + t.entries[i].key);
    }
  });
  return 0;
}
