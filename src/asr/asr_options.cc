// The options of asr-train and asr-decode, registered by the structs that hold them
// (util/options.h), so that bin/asr-*.cc only register, parse and call; --config=FILE comes with
// the command line (e.g. conf/asr-train-proxy.conf).
#include <cmath>

#include "asr/asr.h"
#include "io/common_options.h"
#include "util/error.h"

namespace tsrir {

const Choices<RnnType>& rnn_type_choices() {
  static const Choices<RnnType> choices = {{"gru", RnnType::kGru}, {"lstm", RnnType::kLstm}};
  return choices;
}

const char* rnn_type_name(RnnType type) {
  for (const auto& [name, value] : rnn_type_choices()) {
    if (value == type) return name.c_str();  // the table's own storage: static
  }
  return "gru";
}

void LogMelOptions::Register(OptionsItf* opts) {
  opts->Register("sample-rate", &sample_rate_hz, "Audio is resampled to this rate (Hz)");
  opts->RegisterAlias("sample-frequency", "sample-rate");
  opts->Register("frame-length", &frame_length_ms, "Frame length (ms)");
  opts->Register("frame-shift", &frame_shift_ms, "Frame shift (ms)");
  opts->Register("num-mel-bins", &num_mel_bins, "Mel filters");
  opts->Register("low-freq", &low_hz, "Lowest mel filter edge (Hz)");
  opts->Register("high-freq", &high_hz, "Highest mel filter edge (Hz; <= 0: offset from Nyquist)");
  opts->Register("preemphasis-coefficient", &preemphasis, "Pre-emphasis x[n] - a x[n-1]");
}

void AsrModelConfig::Register(OptionsItf* opts) {
  opts->Register("conv-layers", &conv_layers, "1-D convolution layers");
  opts->Register("conv-channels", &conv_channels, "Channels of the convolutions");
  opts->Register("conv-kernel", &conv_kernel, "Kernel width of the convolutions (odd)");
  opts->Register("subsampling", &subsampling, "Time stride of the first convolution (1..4)");
  opts->RegisterEnum("rnn-type", &rnn_type, rnn_type_choices(), "Recurrent layer type");
  opts->Register("rnn-layers", &rnn_layers, "Bidirectional recurrent layers");
  opts->Register("rnn-hidden", &rnn_hidden, "Hidden units per direction");
  opts->Register("dropout", &dropout, "Dropout after the convolutions, between and after the recurrent layers");
}

void AsrModelConfig::validate() const {
  if (conv_layers < 1 || conv_channels < 1 || conv_kernel < 1 || conv_kernel % 2 == 0) {
    throw Error("--conv-layers and --conv-channels must be >= 1 and --conv-kernel odd");
  }
  if (subsampling < 1 || subsampling > 4) throw Error("--subsampling must be 1..4");
  if (rnn_layers < 1 || rnn_hidden < 1) throw Error("--rnn-layers and --rnn-hidden must be >= 1");
  if (!(dropout >= 0 && dropout < 1)) throw Error("--dropout must be in [0, 1)");
}

void AsrTrainOptions::Register(OptionsItf* opts) {
  opts->Register("epochs", &epochs, "Total training epochs (a resumed run continues to this count)");
  opts->Register("max-minutes", &max_minutes, "Stop after this many minutes of training with a checkpoint (0 = no limit)");
  CommonOptions(opts)
      .seed(&seed, "the initialisation, batch order, masks and dropout")
      .threads(&num_threads, "LibTorch's CPU threads and feature extraction");
  register_compute_device(opts, &device);
  opts->Register("batch-size", &batch_size, "Utterances per step (batches group similar lengths)");
  opts->Register("sample-copies", &sample_copies,
                 "Each epoch trains on one copy per source utterance (the data dir's utt2uniq, as "
                 "reverberate-data --num-replications writes it), drawn from the seed and epoch");
  opts->Register("learning-rate", &learning_rate, "Adam learning rate");
  opts->Register("grad-clip", &grad_clip, "Gradient norm clip");
  model.Register(opts);
  opts->Register("time-masks", &time_masks, "SpecAugment time masks per utterance");
  opts->Register("max-time-mask", &max_time_mask, "Longest time mask as a fraction of the utterance");
  opts->Register("freq-masks", &freq_masks, "SpecAugment frequency masks per utterance");
  opts->Register("max-freq-mask", &max_freq_mask, "Widest frequency mask (mel bins)");
  features.Register(opts);
  opts->Register("resume", &resume, "Continue from <model-dir>/checkpoint.pt (same settings required)");
  opts->Register("progress-interval", &progress_interval_s, "Seconds between progress lines on stderr");
}

void AsrTrainOptions::validate() const {
  model.validate();
  if (epochs < 1) throw Error("--epochs must be >= 1");
  if (batch_size < 1) throw Error("--batch-size must be >= 1");
  if (num_threads < 1) throw Error("--num-threads must be >= 1");
  if (!(learning_rate > 0) || !std::isfinite(learning_rate)) throw Error("--learning-rate must be > 0");
  if (!(grad_clip > 0)) throw Error("--grad-clip must be > 0");
  if (!(max_minutes >= 0)) throw Error("--max-minutes must be >= 0");
  if (!(max_time_mask >= 0 && max_time_mask < 1) || time_masks < 0 || freq_masks < 0 || max_freq_mask < 0) {
    throw Error("SpecAugment settings must be >= 0 (--max-time-mask below 1)");
  }
}

void AsrDecodeOptions::Register(OptionsItf* opts) {
  CommonOptions(opts).threads(&num_threads, "LibTorch's CPU threads and feature extraction");
  register_compute_device(opts, &device);
  opts->Register("batch-size", &batch_size, "Utterances per forward pass");
}

void AsrDecodeOptions::validate() const {
  if (batch_size < 1) throw Error("--batch-size must be >= 1");
  if (num_threads < 1) throw Error("--num-threads must be >= 1");
}

}  // namespace tsrir
