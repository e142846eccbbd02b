// Kaldi rir_list / noise_list lines and the shlex splitting under them. The first byte picks the
// parser. Invariants: a parsed RIR line formatted with format_rir_list_line parses back to the
// same ids and file name (the writer and the reader agree on quoting), and shell_quote() of any
// word splits back to exactly that word (a quoted name never becomes two words or a command).
#include "fuzz_common.h"
#include "io/kaldi_lists.h"
#include "io/shell.h"
#include "util/strings.h"

using namespace tsrir;

namespace {

void check_rir_round_trip(const RirListEntry& e) {
  const std::string line = format_rir_list_line(e);
  RirListEntry back = parse_rir_list_line(line, "formatted");
  FUZZ_CHECK(back.rir_id == e.rir_id, line);
  FUZZ_CHECK(back.room_id == e.room_id, line);
  FUZZ_CHECK(back.receiver_position_id == e.receiver_position_id, line);
  FUZZ_CHECK(back.source_position_id == e.source_position_id, line);
  // Byte for byte, pipes included (a pipe written bare once lost its inner quoting here).
  FUZZ_CHECK(back.rxfilename == e.rxfilename, line);
  FUZZ_CHECK(back.rt60.has_value() == e.rt60.has_value(), line);
  FUZZ_CHECK(back.probability.has_value() == e.probability.has_value(), line);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string line = fuzz::as_text(data + 1, size - 1);
  fuzz::expect_only_errors([&] {
    switch (data[0] % 4) {
      case 0: {
        auto words = shlex_split(line, "fuzz");
        for (const auto& w : words) {
          auto again = shlex_split(shell_quote(w), "quoted");
          FUZZ_CHECK(again.size() == 1 && again[0] == w, "shell_quote/shlex_split disagree on '" + w + "'");
        }
        break;
      }
      case 1:
      case 3: {
        RirListEntry e = parse_rir_list_line(line, "fuzz");
        FUZZ_CHECK(!e.rir_id.empty() && !e.room_id.empty() && !e.rxfilename.empty(), line);
        if (e.probability) FUZZ_CHECK(*e.probability >= 0 && *e.probability <= 1, line);
        check_rir_round_trip(e);
        break;
      }
      case 2: {
        NoiseListEntry e = parse_noise_list_line(line, "fuzz");
        FUZZ_CHECK(!e.noise_id.empty() && !e.rxfilename.empty(), line);
        FUZZ_CHECK(e.noise_type == "isotropic" || e.noise_type == "point-source", line);
        FUZZ_CHECK(!choice_name(bg_fg_type_choices(), e.bg_fg_type).empty(), line);
        if (e.noise_type == "isotropic") FUZZ_CHECK(!e.room_linkage.empty(), line);
        break;
      }
    }
  });
  return 0;
}
