// TS-RIRGAN (Ratnarajah et al., ASRU 2021): a 1-D CycleGAN that translates synthetic RIRs into
// real-like ones, trained on unpaired sets. This header is torch-free; LibTorch is confined to
// the .cc files of src/gan. Architecture, losses and optimiser follow docs/reference/spec-digest.md §3.
#pragma once
#include <cstdint>
#include <string>

#include "gan/compute_device.h"
#include "gan/gan_settings.h"
#include "io/audio_io.h"

namespace tsrir {

class OptionsItf;

// Which generator translates: G_SR (the paper's use) or G_RS.
enum class GanDirection { kSyntheticToReal, kRealToSynthetic };
inline const Choices<GanDirection> kGanDirectionNames = {{"synthetic-to-real", GanDirection::kSyntheticToReal},
                                                         {"real-to-synthetic", GanDirection::kRealToSynthetic}};

struct GanTrainOptions {
  std::string real_list;        // rir scp / rir_list / audio file: the "real" domain
  std::string synthetic_list;   // the "synthetic" domain
  std::string model_dir;        // settings.txt, checkpoint.pt, loss_log.csv
  long long steps = 2000;       // total training iterations (a resumed run continues to this count;
                                // the defaults are judged at 2000: bench/RESULTS.md)
  // The model and how it learns, as stored in settings.txt: the toolkit's defaults, which pass
  // the translation-fidelity suite (tests/gan, bench/RESULTS.md); conf/ts-rirgan-paper.conf
  // restores the paper's. gan_options.cc says where each departs from the paper.
  GanSettings model = default_training_settings();
  int num_threads = 1;
  long long checkpoint_every = 500;  // steps; a checkpoint is always written at exit
  bool resume = false;
  ComputeDevice device = ComputeDevice::kCpu;
  // Collapse guard: every N steps (0: never) G_SR translates a fixed probe batch of synthetic
  // RIRs; training stops with an Error when the outputs are silent or nearly equal to each other
  // while their inputs are not.
  long long collapse_check_every = 100;
  double progress_interval_s = 10.0;
  bool print_settings = false;  // print settings_to_store's settings.txt and train nothing

  void Register(OptionsItf* opts);  // gan_options.cc (model's options nested); the model dir is positional
};

struct GanTrainResult {
  long long first_step = 0;     // first step run by this call (1 for a fresh run)
  long long last_step = 0;      // last completed step (= the checkpoint's step)
  bool interrupted = false;     // SIGINT/SIGTERM: stopped between steps, checkpoint written
  double mean_step_s = 0.0;
  double peak_rss_mb = 0.0;
};

// Trains (or resumes) a model. Throws Error on bad input, on a model dir that does not match the
// options, and on a non-finite loss (the last checkpoint written before it stays in place).
GanTrainResult train_ts_rirgan(const GanTrainOptions& options);

// The settings a new model trained with these options stores in settings.txt: the options' model
// settings with what the chosen generator does not use set to 0, and the lists made absolute
// (ts-rirgan-train --print-settings prints them as that file's text).
GanSettings settings_to_store(const GanTrainOptions& options);

// Output length/level conventions of the translation.
struct GanTranslateOptions {
  std::string model;            // model dir (uses its checkpoint.pt) or a checkpoint file
  std::string input_list;
  std::string out_dir;
  GanDirection direction = GanDirection::kSyntheticToReal;
  int batch_size = 16;
  // Output length in samples at 16 kHz (the original keeps 16000 of the 16384 generated), or -1:
  // the input's length after resampling to 16 kHz, capped at 16384.
  long long keep_length = 16000;
  // false: the generator's output as is (peak-normalised input, tanh output in (-1, 1)), as the
  // original. true: each output is scaled by the input's original peak |x|.
  bool restore_level = false;
  SampleFormat format = SampleFormat::kFloat32;
  ComputeDevice device = ComputeDevice::kCpu;
  int num_threads = 1;
  // float32, or bfloat16: weights and activations in bfloat16 with float32 accumulation
  // (oneDNN); 1.8-2.3x faster translation (bench/RESULTS.md) on CPUs with AVX512-BF16/AMX, output within ~1% RMS of float32
  // (tests/gan/gan_networks_test.cc). Refused where LibTorch sums in bfloat16 (gan_bfloat16.h).
  GanPrecision precision = GanPrecision::kFloat32;
  // A model trained with --generator-average-decay translates with its generator's averaged
  // weights; true: with the last step's instead (a model without an average has only those).
  bool use_last_weights = false;

  void Register(OptionsItf* opts);  // gan_options.cc; input list and out dir are positional
};

struct GanTranslateResult {
  size_t num_rirs = 0;
  double model_load_s = 0.0;
  double translate_s = 0.0;     // reading, model and writing, without the model load
  double peak_rss_mb = 0.0;
};

GanTranslateResult translate_rirs(const GanTranslateOptions& options);

}  // namespace tsrir
