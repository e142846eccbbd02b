// The model dir's settings.txt ("key value" lines): what a checkpoint needs to be rebuilt and
// what a resumed run must agree with. The same text is stored inside each checkpoint.
#pragma once
#include <cstdint>
#include <string>

namespace tsrir {

struct GanSettings {
  int width = 64;
  int kernel_length = 25;
  long long slice_length = 16384;
  double sample_rate_hz = 16000.0;
  int batch_size = 64;
  uint64_t seed = 0;
  double learning_rate = 3e-5;
  int disc_updates = 2;
  // Departures from the original for small CPU models (defaults = the original): kernel init
  // ("glorot" | "he", used only when a model is created) and the generators' L1 loss weights.
  std::string init = "glorot";
  double cycle_weight = 250.0;     // per cycle L1 term (10 * 25)
  double identity_weight = 175.0;  // identity L1 (5 * 35)
  double rmsprop_initial_ms = 1.0;  // RMSProp's initial mean square: 1 (TF, the original) or 0
  // Generator up-path channels: "original" (16w, 8w, 4w: the original's code, 66.6 M parameters
  // per generator at width 64) or "light" (4w, 2w, w: what the original's code comments say,
  // 41.4 M parameters and 1/3 of the FLOPs at width 64). Part of the architecture.
  std::string decoder = "original";
  // "original" (tanh output, the paper) or "residual" (output = input + a learned correction that
  // starts at zero). Part of the architecture. Settings files without the key are "original".
  std::string generator = "original";
  // Linear learning-rate warm-up over the first N steps (0: none, the original).
  long long warmup_steps = 0;
  std::string precision = "float32";  // training arithmetic: "float32" | "bfloat16" (autocast)
  std::string real_list;
  std::string synthetic_list;
};

// Width multipliers of the generator's first three transposed convs for `decoder` (Error if the
// name is neither "original" nor "light").
void decoder_multipliers(const std::string& decoder, int multipliers[3]);

std::string gan_settings_text(const GanSettings& settings);
// `where` names the file for errors (unknown key, bad value, wrong format version).
GanSettings parse_gan_settings(const std::string& text, const std::string& where);
GanSettings read_gan_settings_file(const std::string& path);
void write_gan_settings_file(const std::string& path, const GanSettings& settings);  // atomic

// Errors with a clear message if a resumed run or a loaded checkpoint does not match the model
// its settings describe (width, decoder, kernel, slice, rate); `what` names the two sides.
void check_same_architecture(const GanSettings& expected, const GanSettings& found,
                             const std::string& what);

}  // namespace tsrir
