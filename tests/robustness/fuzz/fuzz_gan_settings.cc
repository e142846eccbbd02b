// TS-RIRGAN's model settings (src/gan/gan_settings.h: settings.txt in a model dir, and the copy
// inside each checkpoint). A resumed run and gas-to-real rebuild the model from this text, so
// invariants: only Error escapes; a text that parses is a supported architecture; written back
// with gan_settings_text it parses again (never an Error) to exactly the same values, and writes
// the same text again (a fixed point, which also covers fields added later).
#include <cstring>

#include "fuzz_common.h"
#include "gan/gan_settings.h"

using namespace tsrir;

namespace {

std::string fields(const GanSettings& s) {
  // Doubles by their bits: "identical values" means bit-identical, not printed alike.
  auto bits = [](double v) {
    uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return std::to_string(b);
  };
  return std::to_string(s.width) + " " + std::to_string(s.kernel_length) + " " + std::to_string(s.slice_length) + " " +
         bits(s.sample_rate_hz) + " " + std::to_string(s.batch_size) + " " + std::to_string(s.seed) + " " +
         bits(s.learning_rate) + " " + std::to_string(s.disc_updates) + " " + choice_name(kGanInitNames, s.init) + " " +
         bits(s.cycle_weight) + " " + bits(s.identity_weight) + " " + bits(s.rmsprop_initial_ms) + " " +
         choice_name(kGanDecoderNames, s.decoder) + " " + choice_name(kGanGeneratorNames, s.generator) + " " +
         choice_name(kGanPrecisionNames, s.precision) + " " + std::to_string(s.warmup_steps) + " [" + s.real_list +
         "] [" + s.synthetic_list + "]";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = fuzz::as_text(data, size);
  fuzz::expect_only_errors([&] {
    const GanSettings s = parse_gan_settings(text, "fuzz/settings.txt");
    FUZZ_CHECK(s.width >= 1 && s.kernel_length >= 1 && s.slice_length == 16384 && s.sample_rate_hz == 16000.0,
               fields(s));
    const std::string written = gan_settings_text(s);
    GanSettings back;
    try {
      back = parse_gan_settings(written, "written");
    } catch (const Error& e) {
      fuzz::fail("written settings must parse back", written + " -> " + e.what());
    }
    FUZZ_CHECK(fields(back) == fields(s), "values changed by write + parse:\n" + fields(s) + "\n" + fields(back) +
                                              "\nwritten:\n" + written);
    FUZZ_CHECK(gan_settings_text(back) == written, written);
    try {
      check_same_architecture(s, back, "round trip");
    } catch (const Error& e) {
      fuzz::fail("a round trip must keep the architecture", e.what());
    }
  });
  return 0;
}
