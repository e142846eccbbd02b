// The model dir's settings.txt ("key value" lines): what a checkpoint needs to be rebuilt and
// what a resumed run must agree with. The same text is stored inside each checkpoint.
#pragma once
#include <cstdint>
#include <string>

namespace tsrir {

class OptionsItf;

struct GanSettings {
  int width = 64;
  int kernel_length = 25;
  long long slice_length = 16384;
  double sample_rate_hz = 16000.0;
  int batch_size = 64;
  uint64_t seed = 0;
  double learning_rate = 3e-5;
  // The discriminators' own learning rate (two time-scale updates, Heusel et al. 2017); 0 = the
  // generators' (the original). Files without the key: 0.
  double disc_learning_rate = 0.0;
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
  // Residual generators only: the correction is low-passed (nothing left from this frequency up,
  // in Hz) before it is added, so the translation can change only the low-frequency part of the RIR, where the
  // geometric simulator's ray assumption fails (room modes, diffraction: the paper's sec. 1-2);
  // above it the input's own acoustics pass unchanged. 0 = full band. Part of the architecture.
  // Settings files without the key: 0.
  double correction_max_hz = 0.0;
  // Generator hidden activation: "relu" (the original) or "leaky_relu" (slope 0.2, as the original's
  // discriminators). With plain ReLUs the small activations of RIR inputs (~1e-2: most samples are
  // a quiet tail) die under RMSProp's first lr-sized bias updates, after which the generator gets no
  // gradient and a residual one stays the identity for good. Part of the architecture. Files
  // without the key: relu.
  std::string generator_activation = "relu";
  // How the two generators are updated per iteration: "sequential" (the original: a G_SR step and
  // then a G_RS step, each on fresh batches with its own forward graph, after the discriminator
  // steps) or "joint" (one forward of both generators on one pair of batches, one summed loss, both
  // stepped; the discriminators then train on those same translations, detached: CycleGAN's
  // reference implementation, about 1.6x fewer generator passes). Files without the key: sequential.
  std::string generator_update = "sequential";
  // Discriminator input augmentation (Zhao et al. 2020's DiffAugment, for small data sets): "none"
  // (the original) or "shift-gain-polarity": every RIR a discriminator sees, real or translated, in
  // its own update and in the generators' adversarial terms, is delayed by 0-50 ms, scaled by
  // 0.6-1 and its polarity flipped at random. None of these changes what the translation must learn
  // (a room's spectral and decay character); they stop a discriminator from memorising the few
  // dozen training RIRs, after which its gradient no longer tells a generator where the real domain
  // lies. Files without the key: none.
  std::string disc_augment = "none";
  // Linear learning-rate warm-up over the first N steps (0: none, the original).
  long long warmup_steps = 0;
  std::string precision = "float32";  // training arithmetic: "float32" | "bfloat16" (autocast)
  std::string real_list;
  std::string synthetic_list;

  // The model's and training's options (gan_options.cc): everything above but the fixed shape
  // (kernel, slice, rate) and the lists, which ts-rirgan-train takes as --real/--synthetic.
  void Register(OptionsItf* opts);
};

// The toolkit's training defaults (gan_options.cc), which depart from the paper's where the
// member initialisers above (the paper's, read for keys an older settings file lacks) do not pass
// the translation-fidelity suite.
GanSettings default_training_settings();

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
