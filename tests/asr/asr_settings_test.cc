// settings.txt of an asr-train model dir, byte for byte: the text the writer made before the
// settings were written from the options' Register calls (golden, below), what a model dir of
// that time holds and what checkpoints store. A stored model must stay readable and a --resume
// must see no difference.
#include <gtest/gtest.h>

#include <tuple>

#include "asr/asr.h"
#include "asr/asr_settings.h"
#include "util/error.h"

namespace tsrir {
namespace {

// Written by asr_settings_text(asr_settings_of(options)) of commit 7a99820 for these options.
const char* const kGoldenSettings =
    "batch-size 8\n"
    "conv-channels 64\n"
    "conv-kernel 3\n"
    "conv-layers 1\n"
    "data-dir /data/train_rvb\n"
    "dropout 0.25\n"
    "format tsrir-asr-ctc-1\n"
    "frame-length-ms 20\n"
    "frame-shift-ms 10\n"
    "freq-masks 1\n"
    "grad-clip 2.5\n"
    "high-hz -400\n"
    "learning-rate 0.0003\n"
    "low-hz 40\n"
    "max-freq-mask 4\n"
    "max-time-mask 0.125\n"
    "num-mel-bins 24\n"
    "preemphasis 0.95\n"
    "rnn-hidden 96\n"
    "rnn-layers 3\n"
    "rnn-type lstm\n"
    "sample-rate 8000\n"
    "seed 18446744073709551615\n"
    "subsampling 3\n"
    "time-masks 3\n";

AsrTrainOptions golden_options() {
  AsrTrainOptions o;
  o.data_dir = "/data/train_rvb";
  o.model_dir = "/exp/asr";  // not a setting
  o.features.sample_rate_hz = 8000;
  o.features.frame_length_ms = 20;
  o.features.frame_shift_ms = 10;
  o.features.num_mel_bins = 24;
  o.features.low_hz = 40;
  o.features.high_hz = -400;
  o.features.preemphasis = 0.95;
  o.model.conv_layers = 1;
  o.model.conv_channels = 64;
  o.model.conv_kernel = 3;
  o.model.subsampling = 3;
  o.model.rnn_type = RnnType::kLstm;
  o.model.rnn_layers = 3;
  o.model.rnn_hidden = 96;
  o.model.dropout = 0.25;
  o.seed = ~Seed{0};  // --seed=-1
  o.batch_size = 8;
  o.learning_rate = 3e-4;
  o.grad_clip = 2.5;
  o.time_masks = 3;
  o.max_time_mask = 0.125;
  o.freq_masks = 1;
  o.max_freq_mask = 4;
  // Run-time options, not settings: a resumed run may change them.
  o.epochs = 7;
  o.max_minutes = 3;
  o.num_threads = 2;
  o.resume = true;
  o.progress_interval_s = 1;
  return o;
}

TEST(AsrSettings, TextIsTheGoldenBytes) {
  EXPECT_EQ(asr_settings_text(asr_settings_of(golden_options())), kGoldenSettings);
}

TEST(AsrSettings, GoldenTextReadsBackAsTheOptions) {
  const AsrSettings stored = parse_asr_settings(kGoldenSettings, "settings.txt");
  EXPECT_EQ(settings_difference(stored, asr_settings_of(golden_options())), "");
  const AsrTrainOptions o = golden_options();
  const auto features = [](const LogMelOptions& f) {
    return std::make_tuple(f.sample_rate_hz, f.frame_length_ms, f.frame_shift_ms, f.num_mel_bins, f.low_hz,
                           f.high_hz, f.preemphasis);
  };
  const auto model = [](const AsrModelConfig& m) {
    return std::make_tuple(m.conv_layers, m.conv_channels, m.conv_kernel, m.subsampling, m.rnn_type, m.rnn_layers,
                           m.rnn_hidden, m.dropout);
  };
  EXPECT_EQ(features(feature_options_of(stored, "settings.txt")), features(o.features));
  EXPECT_EQ(model(model_config_of(stored, "settings.txt")), model(o.model));
}

TEST(AsrSettings, DifferencesNameTheStoredValues) {
  AsrTrainOptions o = golden_options();
  o.model.rnn_type = RnnType::kGru;
  o.learning_rate = 1e-3;
  const AsrSettings stored = parse_asr_settings(kGoldenSettings, "settings.txt");
  EXPECT_EQ(settings_difference(stored, asr_settings_of(o)), " --learning-rate=0.0003 --rnn-type=lstm");
}

TEST(AsrSettings, BadFilesAreErrorsNamingThem) {
  EXPECT_THROW(parse_asr_settings("format tsrir-gan-1\n", "a/settings.txt"), Error);
  EXPECT_THROW(parse_asr_settings("format tsrir-asr-ctc-1\nnovalue\n", "a/settings.txt"), Error);
  std::string bad = kGoldenSettings;
  bad.replace(bad.find("rnn-type lstm"), 13, "rnn-type rnn");
  try {
    parse_asr_settings(bad, "a/settings.txt");
    FAIL() << "rnn-type rnn accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a/settings.txt"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tsrir
