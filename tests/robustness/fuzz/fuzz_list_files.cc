// Whole list files as the programs read them: read_rir_list, read_noise_list (option form or scp
// form, detected from the first line) and read_rir_refs. The first byte picks the reader; the rest
// is the file. Invariants: ids are unique and non-empty, line numbers point into the file.
#include <algorithm>
#include <set>

#include "fuzz_common.h"
#include "io/kaldi_lists.h"
#include "io/rir_set.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string text = fuzz::as_text(data + 1, size - 1);
  static const std::string path = fuzz::scratch_path("list");
  fuzz::write_file(path, text);
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  fuzz::expect_only_errors([&] {
    std::set<std::string> ids;
    switch (data[0] % 3) {
      case 0:
        for (const auto& e : read_rir_list(path)) {
          FUZZ_CHECK(!e.rir_id.empty() && !e.room_id.empty() && !e.rxfilename.empty(), e.rir_id);
          FUZZ_CHECK(e.line >= 1 && e.line <= lines, std::to_string(e.line));
          FUZZ_CHECK(ids.insert(e.rir_id).second, "duplicate id " + e.rir_id);
        }
        break;
      case 1:
        for (const auto& e : read_noise_list(path)) {
          FUZZ_CHECK(!e.noise_id.empty() && !e.rxfilename.empty(), e.noise_id);
          FUZZ_CHECK(e.line >= 1 && e.line <= lines, std::to_string(e.line));
          FUZZ_CHECK(ids.insert(e.noise_id).second, "duplicate id " + e.noise_id);
        }
        break;
      case 2:
        for (const auto& r : read_rir_refs(path, nullptr)) {
          FUZZ_CHECK(!r.id.empty() && !r.rxfilename.empty() && !r.where.empty(), r.id);
          FUZZ_CHECK(ids.insert(r.id).second, "duplicate id " + r.id);
        }
        break;
    }
  });
  return 0;
}
