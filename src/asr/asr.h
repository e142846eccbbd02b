// A compact CTC character recogniser (LibTorch confined to src/asr/*.cc): log-mel features
// (asr_features.h) -> 1-D convolutions (the first one subsamples time) -> layer norm ->
// bidirectional GRU/LSTM layers -> per-frame character posteriors, trained with CTC and
// SpecAugment-style time and frequency masks. Torch-free header.
#pragma once
#include <cstdint>
#include <string>

#include "asr/asr_features.h"
#include "asr/asr_text.h"
#include "gan/compute_device.h"
#include "util/options.h"

namespace tsrir {

enum class RnnType { kGru, kLstm };
const Choices<RnnType>& rnn_type_choices();  // "gru" | "lstm" (also the settings.txt spelling)
const char* rnn_type_name(RnnType type);

struct AsrModelConfig {
  int conv_layers = 2;
  int conv_channels = 256;
  int conv_kernel = 5;
  int subsampling = 2;          // stride of the first convolution
  RnnType rnn_type = RnnType::kGru;
  int rnn_layers = 2;
  int rnn_hidden = 192;         // per direction
  double dropout = 0.1;

  void Register(OptionsItf* opts);
  void validate() const;        // Error naming the option
};

struct AsrTrainOptions {
  std::string data_dir;         // Kaldi data dir with wav.scp, utt2spk, text (segments optional)
  std::string model_dir;        // settings.txt, checkpoint.pt, loss_log.csv
  LogMelOptions features;
  AsrModelConfig model;
  int epochs = 20;              // total epochs (a resumed run continues to this count)
  double max_minutes = 0.0;     // > 0: stop (with a checkpoint) after this much training time
  Seed seed = 0;
  int num_threads = 1;
  // The network, batches and CTC loss on the CPU (deterministic for a --seed and --num-threads) or
  // a CUDA GPU (not bit-reproducible: cuDNN's recurrent layers and CUDA's CTC gradient sum in
  // varying order). Not a setting of the model: a resumed run may change it.
  ComputeDevice device = ComputeDevice::kCpu;
  int batch_size = 16;          // utterances per step (batches are made of similar lengths)
  bool sample_copies = false;   // one reverberant copy per source utterance (utt2uniq) per epoch
  double learning_rate = 1e-3;  // Adam
  double grad_clip = 5.0;       // gradient norm clip
  int time_masks = 2;           // SpecAugment: masks per utterance ...
  double max_time_mask = 0.05;  // ... each up to this fraction of the frames
  int freq_masks = 2;
  int max_freq_mask = 6;        // mel bins
  bool resume = false;
  double progress_interval_s = 10.0;

  // Every option of asr-train (the features' and the network's nested); the two directories are
  // positional arguments, which the program fills in.
  void Register(OptionsItf* opts);
  void validate() const;        // Error naming the option
};

struct AsrTrainResult {
  int first_epoch = 0;          // 1-based epoch where this call started
  int epochs_done = 0;          // complete epochs in the checkpoint
  long long steps_done = 0;
  bool interrupted = false;     // SIGINT/SIGTERM: stopped between steps, checkpoint written
  bool out_of_time = false;     // --max-minutes reached, checkpoint written
  double last_epoch_loss = 0.0; // mean CTC loss per step of the last complete epoch
  long long num_parameters = 0;
  double train_s = 0.0;
  double peak_rss_mb = 0.0;
};

AsrTrainResult train_asr(const AsrTrainOptions& options);

struct AsrDecodeOptions {
  std::string model_dir;
  std::string data_dir;
  std::string out_dir;          // hyp, wer, cer, utt_errors (each written atomically)
  int num_threads = 1;
  ComputeDevice device = ComputeDevice::kCpu;  // any model decodes on either
  int batch_size = 16;

  void Register(OptionsItf* opts);
  void validate() const;
};

struct AsrDecodeResult {
  size_t num_utterances = 0;
  bool scored = false;          // the data dir had a text file
  EditCounts words, characters;
  double decode_s = 0.0;
  double peak_rss_mb = 0.0;
};

AsrDecodeResult decode_asr(const AsrDecodeOptions& options);

}  // namespace tsrir
