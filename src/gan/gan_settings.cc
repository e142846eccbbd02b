#include "gan/gan_settings.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/atomic_output.h"
#include "io/common_options.h"
#include "util/error.h"
#include "util/options.h"
#include "util/strings.h"

namespace tsrir {
namespace {

// The file's keys in the order files have always had them (format first): the bytes of a model
// written before the file followed the options stay the bytes written now.
const std::vector<std::string> kFileOrder = {
    "width", "kernel_length", "slice_length", "sample_rate_hz", "batch_size", "seed", "learning_rate",
    "disc_learning_rate", "disc_updates", "init", "cycle_weight", "identity_weight", "gain_weight",
    "identity_gain_weight", "identity_direct_bands", "identity_direct_weight", "rmsprop_initial_ms", "decoder", "generator", "correction_max_hz", "correction_weight", "generator_activation",
    "generator_update", "disc_augment", "disc_view", "envelope_reference", "envelope_floor_db", "precision", "warmup_steps", "generator_average_decay", "real_list", "synthetic_list"};

SettingsStyle file_style() {
  SettingsStyle style;
  style.sorted = false;
  style.underscores = true;  // "learning_rate" for --learning-rate
  style.double_digits = 17;  // exact: a resumed run compares the values
  style.require_all = false;  // a key added later keeps the paper's value (the member initialiser)
  return style;
}

// A settings file bound to `settings`' fields, every key written.
SettingsFile every_key_file(GanSettings* settings) {
  SettingsFile file("tsrir-ts-rirgan-settings-v1", "a TS-RIRGAN settings file", file_style());
  settings->RegisterStored(&file);
  file.Order(kFileOrder);
  return file;
}

// The model's settings file. Keys added after models were written are left out at their
// defaults, so that those files keep their bytes.
SettingsFile bound_file(GanSettings* settings) {
  SettingsFile file = every_key_file(settings);
  GanSettings defaults;
  file.OmitWhenDefault({"correction-weight", "disc-view", "envelope-reference", "envelope-floor-db", "identity-gain-weight", "identity-direct-bands", "identity-direct-weight", "generator-average-decay"}, every_key_file(&defaults).values());
  return file;
}

// What the networks are built for (gan_networks.h): a file that says otherwise is not a model here.
void check_supported(const GanSettings& s, const std::string& where) {
  check_gan_settings(s, where);
  if (s.kernel_length < 1 || s.slice_length != 16384 || s.sample_rate_hz != 16000.0) {
    throw Error(where + ": unsupported model settings (kernel " + std::to_string(s.kernel_length) + ", slice " +
                std::to_string(s.slice_length) + ")");
  }
}

}  // namespace

void GanSettings::Register(OptionsItf* opts) {
  opts->Register("width", &width, "Model width (64 = the paper's model; 4-16 for CPU experiments)");
  opts->RegisterEnum("decoder", &decoder, kGanDecoderNames,
                  "Generator up path: original (16w,8w,4w channels: the original's code) or light "
                  "(4w,2w,w: its code comments; 41.4 M instead of 66.6 M parameters at width 64, 1/3 of the FLOPs)");
  opts->Register("batch-size", &batch_size, "RIRs per batch (the paper's is 64)");
  CommonOptions(opts).seed(&seed, "the initialisation and batch order");
  opts->Register("learning-rate", &learning_rate, "Generators' RMSProp learning rate (the paper's: 3e-5)");
  opts->Register("disc-learning-rate", &disc_learning_rate,
                 "Discriminators' RMSProp learning rate (0 = --learning-rate, the paper)");
  opts->Register("disc-updates", &disc_updates, "Discriminator updates per generator update (the paper: 2)");
  opts->RegisterEnum("init", &init, kGanInitNames, "Kernel init of a new model (the paper: glorot)");
  opts->Register("rmsprop-initial-ms", &rmsprop_initial_ms,
                 "RMSProp's initial mean square of a new model: 0 or 1 (TF1, the paper)");
  opts->Register("cycle-weight", &cycle_weight, "Generator loss weight per cycle L1 term (the paper: 250)");
  opts->Register("identity-weight", &identity_weight, "Generator loss weight of the identity L1 term (the paper: 175; at 0 the identity passes are "
                 "skipped, a third fewer generator passes per joint step, and the log's identity columns read nan)");
  opts->Register("gain-weight", &gain_weight,
                 "Band-gain generators: weight of the L2 penalty on their log gains (nepers^2) in the generators' loss "
                 "(the paper has no such term)");
  opts->Register("identity-gain-weight", &identity_gain_weight,
                 "Band-gain generators: weight of the L2 penalty on the log gains (nepers^2) they predict after the direct "
                 "sound, and at it below 250 Hz, for RIRs of their own domain, which should pass unchanged (a gain identity; "
                 "0 = none; the paper has no such term)");
  opts->Register("identity-direct-bands", &identity_direct_bands,
                 "Band-gain generators: the gain identity also holds the direct-sound gain of this many of the lowest "
                 "bands (1 = below 250 Hz; 0 = none)");
  opts->Register("identity-direct-weight", &identity_direct_weight,
                 "Band-gain generators: weight of the L2 penalty on the direct-sound log gains of the other bands for RIRs "
                 "of their own domain (a weaker hold than the gain identity's; 0 = none; the paper has no such term)");
  opts->Register("correction-weight", &correction_weight,
                 "Residual and band-gain generators: weight of the L2 penalty on the waveform correction (its mean square "
                 "re the input's) in the generators' loss (0 = none; the paper has no such term)");
  opts->Register("warmup-steps", &warmup_steps, "Ramp the learning rates linearly over the first N steps (0 = none, the paper)");
  opts->Register("generator-average-decay", &generator_average_decay,
                 "Both generators keep an exponential moving average of their weights over the steps, step s weighing "
                 "D^(t-s) at step t (debiased; 1/(1-D) steps' memory), which gas-to-real translates with; training is "
                 "unchanged (0 = none, the paper)");
  opts->RegisterEnum("precision", &precision, kGanPrecisionNames,
                  "Training arithmetic: bfloat16 = CPU autocast, bfloat16 convolutions with float32 weights, "
                  "gradients and losses; faster only on CPUs with AVX512-BF16/AMX (bench/RESULTS.md); refused where "
                  "LibTorch sums bfloat16 products in bfloat16 (probed at start)");
  opts->RegisterEnum("generator", &generator, kGanGeneratorNames,
                  "original (the paper: tanh output rebuilt through the bottleneck), residual (output = "
                  "input + a learned correction, zero before the input's direct sound) or band-gain (the residual's "
                  "correction + a smooth gain per band and time after the direct sound on the input's own band "
                  "signals: the whole band's levels can change)");
  opts->Register("correction-max-hz", &correction_max_hz,
                 "Residual and band-gain generators: the waveform correction is low-passed, nothing left from this frequency up "
                 "(Hz; 0 = full band; the paper has no such limit)");
  opts->RegisterEnum("generator-activation", &generator_activation, kGanActivationNames,
                  "Generator hidden activation (the paper: relu; leaky_relu has slope 0.2)");
  opts->RegisterEnum("disc-augment", &disc_augment, kGanDiscAugmentNames,
                  "Discriminator input augmentation (the paper: none; DiffAugment-style random delay, gain, polarity)");
  opts->RegisterEnum("disc-view", &disc_view, kGanDiscViewNames,
                  "What the discriminators read (the paper: waveform); waveform+envelope adds a critic of each band's "
                  "level in dB per 8 ms frame, where an RIR's quiet late part (each band's decay) weighs as its start; "
                  "waveform+separable-envelope reads each band's levels on its own (one critic per band, their logits "
                  "averaged), so that no band's verdict depends on another's");
  opts->RegisterEnum("envelope-reference", &envelope_map.reference, kGanEnvelopeReferenceNames,
                  "An envelope view's levels are re the RIR's loudest cell (loudest-cell) or re the direct sound "
                  "(direct-sound: the peak +-2.5 ms as one cell of all bands would hold it)");
  opts->Register("envelope-floor-db", &envelope_map.floor_db,
                 "An envelope view's levels are floored this far below their reference (dB, in [-120, -20]): "
                 "nothing below it is judged");
  opts->RegisterEnum("generator-update", &generator_update, kGanGeneratorUpdateNames,
                  "sequential (the paper: G_SR then G_RS, each on fresh batches) or joint (CycleGAN's "
                  "reference: both generators from one forward, one summed loss)");
}

// The file holds what Register declares and the fixed shape and the lists, which are not options.
void GanSettings::RegisterStored(OptionsItf* opts) {
  Register(opts);
  opts->Register("kernel-length", &kernel_length, "Convolution kernel length (fixed: 25)");
  opts->Register("slice-length", &slice_length, "RIR length in samples (fixed: 16384)");
  opts->Register("sample-rate-hz", &sample_rate_hz, "Sample rate (fixed: 16000)");
  opts->Register("real-list", &real_list, "The real RIRs the model was trained on");
  opts->Register("synthetic-list", &synthetic_list, "The synthetic RIRs the model was trained on");
}

void check_gan_settings(const GanSettings& s, const std::string& file) {
  auto require = [&file](bool ok, std::string option, const char* rule) {
    if (ok) return;
    if (file.empty()) throw Error("--" + option + " must be " + rule);
    std::replace(option.begin(), option.end(), '-', '_');
    throw Error(file + ": " + option + " must be " + rule);
  };
  auto non_negative = [](double x) { return x >= 0 && std::isfinite(x); };
  require(s.width >= 1 && s.width <= 1024, "width", "in [1, 1024]");
  require(s.batch_size >= 1, "batch-size", ">= 1");
  require(s.disc_updates >= 1, "disc-updates", ">= 1");
  require(s.learning_rate > 0 && std::isfinite(s.learning_rate), "learning-rate", "> 0");
  require(non_negative(s.disc_learning_rate), "disc-learning-rate", ">= 0");
  require(s.rmsprop_initial_ms == 0.0 || s.rmsprop_initial_ms == 1.0, "rmsprop-initial-ms", "1 or 0");
  require(non_negative(s.cycle_weight), "cycle-weight", ">= 0");
  require(non_negative(s.identity_weight), "identity-weight", ">= 0");
  require(non_negative(s.gain_weight), "gain-weight", ">= 0");
  require(non_negative(s.identity_gain_weight), "identity-gain-weight", ">= 0");
  require(non_negative(s.correction_weight), "correction-weight", ">= 0");
  // 11: the band-gain generator's bands (gan_band_gain.h; that header needs LibTorch).
  require(s.identity_direct_bands >= 0 && s.identity_direct_bands <= 11, "identity-direct-bands", "in [0, 11]");
  require(non_negative(s.identity_direct_weight), "identity-direct-weight", ">= 0");
  require(s.warmup_steps >= 0, "warmup-steps", ">= 0");
  require(s.generator_average_decay >= 0 && s.generator_average_decay < 1, "generator-average-decay", "in [0, 1)");
  require(s.correction_max_hz >= 0 && s.correction_max_hz < 8000, "correction-max-hz", "in (0, 8000) or 0");
  require(s.envelope_map.floor_db >= -120 && s.envelope_map.floor_db <= -20, "envelope-floor-db", "in [-120, -20]");
  // A map no critic reads is a mistake the user should hear of, not a setting stored for nothing.
  const GanEnvelopeMap first_form;
  const bool map_asked = s.envelope_map.reference != first_form.reference || s.envelope_map.floor_db != first_form.floor_db;
  require(!map_asked || s.disc_view != GanDiscView::kWaveform, "envelope-reference",
          "left at loudest-cell, and --envelope-floor-db at -80, unless --disc-view has an envelope");
}

SettingsValues gan_settings_values(const GanSettings& settings) {
  GanSettings copy = settings;
  return bound_file(&copy).values();
}

std::string gan_settings_text(const GanSettings& settings) {
  GanSettings copy = settings;
  return bound_file(&copy).text();
}

GanSettings parse_gan_settings(const std::string& text, const std::string& where) {
  GanSettings s;
  bound_file(&s).parse(text, where);
  check_supported(s, where);
  return s;
}

void decoder_multipliers(GanDecoder decoder, int multipliers[3]) {
  if (decoder == GanDecoder::kOriginal) {
    multipliers[0] = 16, multipliers[1] = 8, multipliers[2] = 4;
  } else {
    multipliers[0] = 4, multipliers[1] = 2, multipliers[2] = 1;
  }
}

GanSettings read_gan_settings_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read model settings " + path);
  std::ostringstream os;
  os << in.rdbuf();
  return parse_gan_settings(os.str(), path);
}

void write_gan_settings_file(const std::string& path, const GanSettings& settings) {
  AtomicTextFile out(path);
  out.stream() << gan_settings_text(settings);
  out.commit();
}

namespace {
std::string envelope_map_text(const GanSettings& s) {
  if (s.disc_view == GanDiscView::kWaveform) return "";
  return " (levels re " + choice_name(kGanEnvelopeReferenceNames, s.envelope_map.reference) + ", floor " +
         format_double(s.envelope_map.floor_db, 6) + " dB)";
}

std::string architecture_text(const GanSettings& s) {
  return "width " + std::to_string(s.width) + " (decoder " + choice_name(kGanDecoderNames, s.decoder) + ", generator " +
         choice_name(kGanGeneratorNames, s.generator) + ", correction max " + format_double(s.correction_max_hz, 6) +
         " Hz, activation " + choice_name(kGanActivationNames, s.generator_activation) +
         ", discriminators' view " + choice_name(kGanDiscViewNames, s.disc_view) + envelope_map_text(s) + ", kernel " +
         std::to_string(s.kernel_length) + ")";
}
}  // namespace

void check_same_architecture(const GanSettings& expected, const GanSettings& found,
                             const std::string& what) {
  if (expected.width != found.width || expected.kernel_length != found.kernel_length ||
      expected.slice_length != found.slice_length || expected.sample_rate_hz != found.sample_rate_hz ||
      expected.decoder != found.decoder || expected.generator != found.generator ||
      expected.correction_max_hz != found.correction_max_hz ||
      expected.generator_activation != found.generator_activation || expected.disc_view != found.disc_view ||
      expected.envelope_map.reference != found.envelope_map.reference ||
      expected.envelope_map.floor_db != found.envelope_map.floor_db) {
    throw Error(what + ": model " + architecture_text(found) + ", expected " + architecture_text(expected));
  }
}

}  // namespace tsrir
