// The strict number parsers behind every option value and list field. Invariants: parse_double
// returns finite values and format_double(v, 17) reads back exactly; parse_int agrees with a
// wider-range reference; parse_double_list yields one value per field.
#include <cmath>

#include "fuzz_common.h"
#include "util/strings.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string text = fuzz::as_text(data + 1, size - 1);
  fuzz::expect_only_errors([&] {
    switch (data[0] % 4) {
      case 0: {
        double v = parse_double(text, "fuzz");
        FUZZ_CHECK(std::isfinite(v), text);
        FUZZ_CHECK(parse_double(format_double(v, 17), "again") == v, text);
        break;
      }
      case 1: {
        long long v = parse_int(text, "fuzz");
        FUZZ_CHECK(parse_int(std::to_string(v), "again") == v, text);
        break;
      }
      case 2:
        parse_bool(text, "fuzz");
        break;
      case 3: {
        auto v = parse_double_list(text, ',', "fuzz");
        FUZZ_CHECK(v.size() == split(text, ',').size(), text);
        break;
      }
    }
  });
  return 0;
}
