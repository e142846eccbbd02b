// rir-eq's model files (src/eq/eq_model.h). Invariants: a model that parses is a valid mixture
// whose draws are finite gains; written back with write_eq_model it parses to the same numbers
// (written with 17 significant digits: exact).
#include <cmath>
#include <sstream>

#include "eq/eq_model.h"
#include "fuzz_common.h"
#include "util/rng.h"

using namespace tsrir;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = fuzz::as_text(data, size);
  fuzz::expect_only_errors([&] {
    EqModel m = parse_eq_model(text, "fuzz.eq");
    Rng rng(1);
    for (int i = 0; i < 4; ++i) {
      RelativeGainsDb g = draw_target_gains(m, rng);
      for (double x : g) FUZZ_CHECK(std::isfinite(x), "non-finite target gain drawn from a valid model");
    }
    std::ostringstream out;
    write_eq_model(m, out);
    EqModel back;
    try {
      back = parse_eq_model(out.str(), "written");
    } catch (const Error& e) {
      fuzz::fail("a written model must parse back", out.str() + " -> " + e.what());
    }
    FUZZ_CHECK(back.mixture.components.size() == m.mixture.components.size(), out.str());
    for (size_t k = 0; k < m.mixture.components.size(); ++k) {
      const auto& a = m.mixture.components[k];
      const auto& b = back.mixture.components[k];
      FUZZ_CHECK(a.weight == b.weight && a.mean == b.mean && a.covariance == b.covariance, out.str());
    }
  });
  return 0;
}
