// The TS-RIRGAN programs' options, registered by their library structs (util/options.h), so that
// ts-rirgan-train and gas-to-real are thin mains and every option is named, checked and documented
// here once. Choices are registered as typed choices: a wrong value is refused at parse time with
// the list of valid ones, and --help shows them.
#include <string>

#include "gan/compute_device.h"
#include "gan/ts_rirgan.h"
#include "io/common_options.h"
#include "util/error.h"
#include "util/options.h"
#include "util/strings.h"

namespace tsrir {

GanSettings default_training_settings() {
  GanSettings s;  // the paper's, then the departures (README, ts-rirgan-train --help):
  s.decoder = GanDecoder::kLight;  // the up path of the original's code comments, 1/3 of the FLOPs
  s.learning_rate = 3e-5;       // the paper's, for the generators
  s.disc_learning_rate = 1e-4;  // paper: the generators' (two time-scale updates)
  s.disc_updates = 1;           // paper: 2
  s.init = GanInit::kHe;        // paper: glorot
  s.cycle_weight = 25.0;        // paper: 250 (with 175 identity, the L1 terms hold the correction at zero)
  s.identity_weight = 0.0;      // paper: 175
  s.rmsprop_initial_ms = 0.0;   // paper: 1 (TF1)
  s.warmup_steps = 100;         // paper: 0
  s.generator = GanGenerator::kResidual;  // paper: original (tanh; small models paste one template)
  s.correction_max_hz = 500.0;  // paper: no such limit
  // Acts on --generator=band-gain only (opt-in until it passes the fidelity suite's seeds per
  // kind: bench/RESULTS.md); paper: no such term.
  s.gain_weight = 1.0;
  s.generator_update = GanGeneratorUpdate::kJoint;  // paper: sequential
  return s;
}

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
  opts->Register("warmup-steps", &warmup_steps, "Ramp the learning rates linearly over the first N steps (0 = none, the paper)");
  opts->RegisterEnum("precision", &precision, kGanPrecisionNames,
                  "Training arithmetic: bfloat16 = CPU autocast, bfloat16 convolutions with float32 weights, "
                  "gradients and losses; faster only on CPUs with AVX512-BF16/AMX (bench/RESULTS.md)");
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
  opts->RegisterEnum("generator-update", &generator_update, kGanGeneratorUpdateNames,
                  "sequential (the paper: G_SR then G_RS, each on fresh batches) or joint (CycleGAN's "
                  "reference: both generators from one forward, one summed loss)");
}

void GanTrainOptions::Register(OptionsItf* opts) {
  opts->Register("real", &real_list, "Real RIRs: rir scp, rir_list or one audio file");
  opts->Register("synthetic", &synthetic_list, "Synthetic RIRs: rir scp, rir_list or one audio file");
  opts->Register("steps", &steps,
                 "Total training iterations (each: --disc-updates x (D_R, D_S) updates and the generator update)");
  model.Register(opts);
  CommonOptions(opts).threads(&num_threads, "LibTorch's CPU threads (OpenBLAS is kept at 1)");
  opts->Register("checkpoint-every", &checkpoint_every, "Write checkpoint.pt every N steps");
  opts->Register("resume", &resume, "Continue from <model-dir>/checkpoint.pt (same settings required)");
  register_compute_device(opts, &device);
  opts->Register("collapse-check-every", &collapse_check_every,
                 "Every N steps translate a fixed probe batch and stop with an error if the outputs are "
                 "silent or nearly equal across inputs (0 = never)");
  opts->Register("progress-interval", &progress_interval_s, "Seconds between progress lines on stderr");
}

void GanTranslateOptions::Register(OptionsItf* opts) {
  opts->Register("model", &model, "Model dir (ts-rirgan-train output) or its checkpoint.pt (required)");
  opts->RegisterEnum("direction", &direction, kGanDirectionNames,
                  "G_SR (the paper's use) or G_RS");
  opts->Register("batch-size", &batch_size, "RIRs per generator call");
  OptionSpec length;
  length.name = "keep-length";
  length.help = "Output length: samples (1..16384) or 'input' (the input's length at 16 kHz, at most 16384)";
  length.default_text = keep_length < 0 ? "input" : std::to_string(keep_length);
  length.set = [this](const std::string& text) {
    keep_length = text == "input" ? -1 : parse_int(text, "--keep-length");
  };
  opts->RegisterSpec(std::move(length));
  opts->Register("restore-level", &restore_level, "Scale each output by its input's peak |x|");
  CommonOptions(opts).audio_format(&format);
  register_compute_device(opts, &device);
  CommonOptions(opts).threads(&num_threads, "LibTorch's CPU threads and reading");
  opts->RegisterEnum("precision", &precision, kGanPrecisionNames,
                  "bfloat16: faster on CPUs with AVX512-BF16/AMX (slower without), output within ~1% RMS "
                  "of float32 (bench/RESULTS.md)");
}

}  // namespace tsrir
