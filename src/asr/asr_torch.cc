// The network, CTC training and greedy decoding: the only translation unit of src/asr that
// includes LibTorch (each such unit costs ~12 s and 1.4 GB to compile).
#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "asr/asr.h"
#include "asr/asr_batches.h"
#include "asr/asr_data.h"
#include "asr/asr_settings.h"
#include "gan/gan_runtime.h"
#include "gan/gan_tensor_allocator.h"
#include "io/atomic_output.h"
#include "io/owned_output.h"
#include "util/error.h"
#include "util/log.h"
#include "util/rng.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace tsrir {
namespace {

constexpr const char* kCheckpointTag = "tsrir-asr-ctc-checkpoint-1";
constexpr const char* kLogHeader = "step,epoch,batch,loss,step_s";

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// ---- the network ----
struct CtcModelImpl : torch::nn::Module {
  CtcModelImpl(const AsrModelConfig& c, int num_bins) : config(c) {
    int in = num_bins;
    for (int i = 0; i < c.conv_layers; ++i) {
      auto conv = torch::nn::Conv1d(torch::nn::Conv1dOptions(in, c.conv_channels, c.conv_kernel)
                                        .stride(i == 0 ? c.subsampling : 1)
                                        .padding(c.conv_kernel / 2));
      convs.push_back(register_module("conv" + std::to_string(i), conv));
      in = c.conv_channels;
    }
    norm = register_module("norm", torch::nn::LayerNorm(torch::nn::LayerNormOptions({int64_t(in)})));
    const double between = c.rnn_layers > 1 ? c.dropout : 0.0;
    if (c.rnn_type == RnnType::kGru) {
      gru = register_module("rnn", torch::nn::GRU(torch::nn::GRUOptions(in, c.rnn_hidden)
                                                      .num_layers(c.rnn_layers)
                                                      .bidirectional(true)
                                                      .batch_first(true)
                                                      .dropout(between)));
    } else {
      lstm = register_module("rnn", torch::nn::LSTM(torch::nn::LSTMOptions(in, c.rnn_hidden)
                                                        .num_layers(c.rnn_layers)
                                                        .bidirectional(true)
                                                        .batch_first(true)
                                                        .dropout(between)));
    }
    output = register_module("output", torch::nn::Linear(2 * c.rnn_hidden, kNumCharTokens));
  }

  int64_t output_length(int64_t frames) const {
    const int64_t pad = config.conv_kernel / 2;
    return (frames + 2 * pad - config.conv_kernel) / config.subsampling + 1;
  }

  // x: [B, T, D]; lengths: [B] int64 (CPU). Returns log-probabilities [B, T', tokens].
  torch::Tensor forward(torch::Tensor x, const torch::Tensor& lengths, torch::Tensor* out_lengths) {
    x = x.transpose(1, 2);
    for (auto& conv : convs) x = torch::relu(conv->forward(x));
    x = norm->forward(x.transpose(1, 2));
    x = torch::dropout(x, config.dropout, is_training());
    torch::Tensor lens = lengths.clone();
    for (int64_t b = 0; b < lens.size(0); ++b) lens[b] = output_length(lengths[b].item<int64_t>());
    *out_lengths = lens;
    auto packed = torch::nn::utils::rnn::pack_padded_sequence(x, lens, /*batch_first=*/true,
                                                              /*enforce_sorted=*/false);
    torch::nn::utils::rnn::PackedSequence y = gru ? std::get<0>(gru->forward_with_packed_input(packed))
                                                  : std::get<0>(lstm->forward_with_packed_input(packed));
    torch::Tensor h = std::get<0>(torch::nn::utils::rnn::pad_packed_sequence(y, /*batch_first=*/true, 0.0,
                                                                              x.size(1)));
    h = torch::dropout(h, config.dropout, is_training());
    return torch::log_softmax(output->forward(h), 2);
  }

  AsrModelConfig config;
  std::vector<torch::nn::Conv1d> convs;
  torch::nn::LayerNorm norm{nullptr};
  torch::nn::GRU gru{nullptr};
  torch::nn::LSTM lstm{nullptr};
  torch::nn::Linear output{nullptr};
};
TORCH_MODULE(CtcModel);

long long count_parameters(CtcModel& model) {
  long long n = 0;
  for (const auto& p : model->parameters()) n += p.numel();
  return n;
}

// A batch as a padded [B, T, D] tensor, with SpecAugment masks when `rng_key` is set.
torch::Tensor make_batch(const std::vector<const AsrUtterance*>& utts, torch::Tensor* lengths,
                         const AsrTrainOptions* masking, const std::string& mask_key) {
  const int64_t B = int64_t(utts.size());
  int64_t T = 0;
  const int64_t D = int64_t(utts[0]->features.num_bins);
  for (const auto* u : utts) T = std::max<int64_t>(T, int64_t(u->features.num_frames));
  torch::Tensor x = torch::zeros({B, T, D});
  *lengths = torch::empty({B}, torch::kInt64);
  for (int64_t b = 0; b < B; ++b) {
    const FeatureMatrix& f = utts[b]->features;
    float* dst = x[b].data_ptr<float>();
    std::copy(f.values.begin(), f.values.end(), dst);
    (*lengths)[b] = int64_t(f.num_frames);
    if (masking) {
      // Masked cells become 0 (the normalised mean). Draws depend on (seed, key, utterance) only.
      Rng rng = Rng::for_item(masking->seed, mask_key + "/" + utts[b]->id);
      const int64_t frames = int64_t(f.num_frames);
      const int64_t max_t = int64_t(masking->max_time_mask * frames);
      for (int m = 0; m < masking->time_masks && max_t > 0; ++m) {
        const int64_t width = int64_t(rng.below(uint64_t(max_t) + 1));
        const int64_t start = int64_t(rng.below(uint64_t(std::max<int64_t>(1, frames - width))));
        for (int64_t t = start; t < std::min(frames, start + width); ++t) std::fill_n(dst + t * D, D, 0.0f);
      }
      for (int m = 0; m < masking->freq_masks && masking->max_freq_mask > 0; ++m) {
        const int64_t width = int64_t(rng.below(uint64_t(masking->max_freq_mask) + 1));
        const int64_t start = int64_t(rng.below(uint64_t(std::max<int64_t>(1, D - width))));
        for (int64_t t = 0; t < frames; ++t) {
          for (int64_t d = start; d < std::min(D, start + width); ++d) dst[t * D + d] = 0.0f;
        }
      }
    }
  }
  return x;
}

struct Progress {
  int epoch = 0;            // complete epochs
  long long batch = 0;      // next batch of the current epoch
  long long step = 0;       // optimiser steps so far
  double epoch_loss_sum = 0.0;  // over the current epoch's steps so far
  double last_epoch_loss = 0.0;
};

void save_checkpoint(const std::string& path, const std::string& settings_text, CtcModel& model,
                     torch::optim::Adam& optimizer, const Progress& p) {
  torch::serialize::OutputArchive archive, model_archive, optimizer_archive;
  archive.write("format", c10::IValue(std::string(kCheckpointTag)));
  archive.write("settings", c10::IValue(settings_text));
  archive.write("epoch", torch::tensor(int64_t(p.epoch)));
  archive.write("batch", torch::tensor(int64_t(p.batch)));
  archive.write("step", torch::tensor(int64_t(p.step)));
  archive.write("epoch_loss_sum", torch::tensor(p.epoch_loss_sum, torch::kFloat64));
  archive.write("last_epoch_loss", torch::tensor(p.last_epoch_loss, torch::kFloat64));
  model->save(model_archive);
  optimizer.save(optimizer_archive);
  archive.write("model", model_archive);
  archive.write("optimizer", optimizer_archive);
  const std::string temp = make_temp_path(path);
  try {
    archive.save_to(temp);
  } catch (const std::exception& e) {
    discard_temp_path(temp);
    throw Error("cannot write checkpoint " + path + ": " + std::string(e.what()).substr(0, 200));
  }
  commit_temp_path(temp, path);
}

// Tensors are read onto `device` (where they were saved does not matter: a model trained on a GPU
// decodes on the CPU and the other way round).
void open_checkpoint(const std::string& path, torch::serialize::InputArchive& archive, torch::Device device) {
  try {
    archive.load_from(path, device);
  } catch (const std::exception& e) {
    std::string why = e.what();
    throw Error(path + ": not a readable asr-train checkpoint (" + why.substr(0, why.find('\n')) + ")");
  }
  c10::IValue tag;
  if (!archive.try_read("format", tag) || !tag.isString() || tag.toStringRef() != kCheckpointTag) {
    throw Error(path + ": not an asr-train checkpoint (no '" + std::string(kCheckpointTag) + "' tag)");
  }
}

int64_t read_int(torch::serialize::InputArchive& a, const std::string& key, const std::string& path) {
  torch::Tensor t;
  if (!a.try_read(key, t)) throw Error(path + ": checkpoint lacks '" + key + "'");
  return t.item<int64_t>();
}

double read_real(torch::serialize::InputArchive& a, const std::string& key, const std::string& path) {
  torch::Tensor t;
  if (!a.try_read(key, t)) throw Error(path + ": checkpoint lacks '" + key + "'");
  return t.item<double>();
}

void load_model(torch::serialize::InputArchive& archive, CtcModel& model, const std::string& path) {
  torch::serialize::InputArchive model_archive;
  if (!archive.try_read("model", model_archive)) throw Error(path + ": checkpoint lacks the model");
  try {
    model->load(model_archive);
  } catch (const std::exception& e) {
    std::string why = e.what();
    throw Error(path + ": the stored model does not match its settings (" + why.substr(0, why.find('\n')) + ")");
  }
}

// Keeps the loss log rows up to `step` (rows of an interrupted run after its checkpoint are
// run again).
std::vector<std::string> read_log_rows(const std::string& path, long long step) {
  std::vector<std::string> rows;
  std::ifstream in(path);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (header) {
      header = false;
      continue;
    }
    const long long s = std::atoll(line.substr(0, line.find(',')).c_str());
    if (s >= 1 && s <= step) rows.push_back(line);
  }
  return rows;
}

void write_log(const std::string& path, const std::vector<std::string>& rows) {
  AtomicTextFile out(path);
  out.stream() << kLogHeader << '\n';
  for (const auto& r : rows) out.stream() << r << '\n';
  out.commit();
}

torch::Device torch_device_of(ComputeDevice device) {
  require_compute_device(device);  // the error a user needs, before any data is read
  return device == ComputeDevice::kCuda ? torch::Device(torch::kCUDA) : torch::Device(torch::kCPU);
}

// The utterances with a transcript (others are reported and skipped) and their character targets.
std::vector<AsrUtterance> load_training_set(const AsrTrainOptions& o, std::vector<std::vector<int>>* targets) {
  const auto load_start = Clock::now();
  std::vector<AsrUtterance> all = load_asr_utterances(o.data_dir, o.features, true, o.num_threads, run_inputs());
  std::vector<AsrUtterance> utts;
  size_t empty = 0;
  for (auto& u : all) {
    if (u.text.empty()) ++empty;
    else utts.push_back(std::move(u));
  }
  if (empty > 0) log_warning(o.data_dir + "/text: " + std::to_string(empty) + " utterance(s) without letters skipped");
  if (utts.empty()) throw Error(o.data_dir + ": no utterance with a transcript to train on");
  targets->assign(utts.size(), {});
  double hours = 0.0;
  for (size_t i = 0; i < utts.size(); ++i) {
    (*targets)[i] = encode_characters(utts[i].text);
    hours += utts[i].features.num_frames * o.features.frame_shift_ms / 3.6e6;
  }
  log_info("loaded " + std::to_string(utts.size()) + " utterances (" + format_double(hours, 3) + " h) from " +
           o.data_dir + " in " + format_double(seconds_since(load_start), 3) + " s");
  return utts;
}

// Model, optimiser state and progress of `path`, read onto the model's device.
Progress resume_from(const std::string& path, CtcModel& model, torch::optim::Adam& optimizer, torch::Device device) {
  torch::serialize::InputArchive archive;
  open_checkpoint(path, archive, device);
  load_model(archive, model, path);
  torch::serialize::InputArchive optimizer_archive;
  if (!archive.try_read("optimizer", optimizer_archive)) throw Error(path + ": checkpoint lacks the optimiser");
  optimizer.load(optimizer_archive);
  Progress p;
  p.epoch = int(read_int(archive, "epoch", path));
  p.batch = read_int(archive, "batch", path);
  p.step = read_int(archive, "step", path);
  p.epoch_loss_sum = read_real(archive, "epoch_loss_sum", path);
  p.last_epoch_loss = read_real(archive, "last_epoch_loss", path);
  return p;
}

// One optimiser step on the utterances `members`; returns the batch's mean CTC loss. The batch
// is made (and masked) on the CPU and moved; the lengths stay on the CPU, where packing and the
// CTC loss read them.
double train_step(CtcModel& model, torch::optim::Adam& optimizer, const AsrTrainOptions& o, torch::Device device,
                  const std::vector<AsrUtterance>& utts, const std::vector<std::vector<int>>& targets,
                  const std::vector<size_t>& members, const Progress& p) {
  namespace F = torch::nn::functional;
  std::vector<const AsrUtterance*> batch_utts;
  std::vector<int64_t> flat_targets, target_lengths;
  for (size_t i : members) {
    batch_utts.push_back(&utts[i]);
    flat_targets.insert(flat_targets.end(), targets[i].begin(), targets[i].end());
    target_lengths.push_back(int64_t(targets[i].size()));
  }
  torch::Tensor lengths, out_lengths;
  torch::Tensor x = make_batch(batch_utts, &lengths, &o, "mask/epoch/" + std::to_string(p.epoch)).to(device);
  // Dropout draws depend on (seed, step) only, so a resumed run repeats them.
  torch::manual_seed(o.seed * 1000003ULL + uint64_t(p.step));
  torch::Tensor log_probs = model->forward(x, lengths, &out_lengths);
  torch::Tensor loss = F::ctc_loss(log_probs.transpose(0, 1), torch::tensor(flat_targets, torch::kInt64).to(device),
                                   out_lengths, torch::tensor(target_lengths, torch::kInt64),
                                   F::CTCLossFuncOptions().blank(kCtcBlank).zero_infinity(true).reduction(torch::kMean));
  const double value = loss.item<double>();
  if (!std::isfinite(value)) {
    throw Error("CTC loss is not finite at step " + std::to_string(p.step + 1) +
                " (the last checkpoint stays in place; try a lower --learning-rate)");
  }
  optimizer.zero_grad();
  loss.backward();
  torch::nn::utils::clip_grad_norm_(model->parameters(), o.grad_clip);
  optimizer.step();
  return value;
}

}  // namespace

AsrTrainResult train_asr(const AsrTrainOptions& o) {
  o.validate();
  const torch::Device device = torch_device_of(o.device);
  tune_memory_for_torch();
  set_openblas_threads(1);
  torch::set_num_threads(o.num_threads);

  const AsrSettings settings = asr_settings_of(o);
  const std::string settings_text = asr_settings_text(settings);
  const std::string settings_path = (fs::path(o.model_dir) / "settings.txt").string();
  const std::string checkpoint_path = (fs::path(o.model_dir) / "checkpoint.pt").string();
  const std::string log_path = (fs::path(o.model_dir) / "loss_log.csv").string();
  if (o.resume) {
    if (!fs::exists(checkpoint_path)) throw Error("--resume: no checkpoint " + checkpoint_path);
    const std::string diff = settings_difference(read_asr_settings(settings_path), settings);
    if (!diff.empty()) {
      throw Error(settings_path + ": the model was trained with" + diff +
                  "; --resume continues exactly, so give the same settings (--epochs may grow)");
    }
  } else if (fs::exists(checkpoint_path)) {
    throw Error(o.model_dir + " already holds a checkpoint; use --resume to continue it, or another dir");
  }

  std::vector<std::vector<int>> targets;
  const std::vector<AsrUtterance> utts = load_training_set(o, &targets);

  // The model dir is the toolkit's (io/owned_output.h): never a user's dir, never an input.
  claim_output_dir(o.model_dir, {"settings.txt", "checkpoint.pt", "loss_log.csv"});
  fs::create_directories(o.model_dir);
  if (!o.resume) write_asr_settings(settings_path, settings);

  torch::manual_seed(o.seed);
  CtcModel model(o.model, o.features.num_mel_bins);  // initialised on the CPU: the same draws on any device
  model->to(device);
  torch::optim::Adam optimizer(model->parameters(), torch::optim::AdamOptions(o.learning_rate));
  Progress p;
  std::vector<std::string> log_rows;
  if (o.resume) {
    p = resume_from(checkpoint_path, model, optimizer, device);
    log_rows = read_log_rows(log_path, p.step);
    log_info("resuming from " + checkpoint_path + " after epoch " + std::to_string(p.epoch) + ", batch " +
             std::to_string(p.batch) + " (step " + std::to_string(p.step) + ")");
  }

  AsrTrainResult result;
  result.num_parameters = count_parameters(model);
  result.first_epoch = p.epoch + 1;
  log_info("model: " + std::to_string(result.num_parameters) + " parameters (" + std::to_string(o.model.conv_layers) +
           " conv x " + std::to_string(o.model.conv_channels) + ", " + std::to_string(o.model.rnn_layers) + " bi-" +
           rnn_type_name(o.model.rnn_type) + " x " + std::to_string(o.model.rnn_hidden) + "), " + std::to_string(o.num_threads) +
           " thread(s), device " + compute_device_name(o.device));

  const EpochBatcher batcher(utts, o.batch_size, o.seed, o.sample_copies);
  if (o.sample_copies) {
    log_info("one copy per source utterance per epoch: " + std::to_string(batcher.num_groups()) + " sources, " +
             std::to_string(utts.size()) + " copies (utt2uniq)");
  }
  const auto start = Clock::now();
  auto last_progress = start;
  StopRequestGuard stop;
  const auto checkpoint = [&]() {
    save_checkpoint(checkpoint_path, settings_text, model, optimizer, p);
    write_log(log_path, log_rows);
  };
  model->train();
  while (p.epoch < o.epochs) {
    const std::vector<std::vector<size_t>> batches = batcher.epoch_batches(p.epoch);
    while (p.batch < (long long)batches.size()) {
      if (stop.stop_requested() || (o.max_minutes > 0 && seconds_since(start) > 60.0 * o.max_minutes)) {
        (stop.stop_requested() ? result.interrupted : result.out_of_time) = true;
        checkpoint();
        log_info(std::string(result.interrupted ? "interrupted" : "--max-minutes reached") + ": checkpoint at epoch " +
                 std::to_string(p.epoch + 1) + " batch " + std::to_string(p.batch) + " written; --resume continues");
        result.epochs_done = p.epoch;
        result.steps_done = p.step;
        result.last_epoch_loss = p.last_epoch_loss;
        result.train_s = seconds_since(start);
        result.peak_rss_mb = peak_rss_mb();
        return result;
      }
      const auto step_start = Clock::now();
      const double value = train_step(model, optimizer, o, device, utts, targets, batches[size_t(p.batch)], p);
      ++p.step;
      ++p.batch;
      p.epoch_loss_sum += value;
      std::ostringstream row;
      row.precision(7);
      row << p.step << ',' << p.epoch + 1 << ',' << p.batch << ',' << value << ',';
      row.precision(4);
      row << seconds_since(step_start);
      log_rows.push_back(row.str());
      if (seconds_since(last_progress) >= o.progress_interval_s) {
        last_progress = Clock::now();
        log_info("epoch " + std::to_string(p.epoch + 1) + "/" + std::to_string(o.epochs) + " batch " +
                 std::to_string(p.batch) + "/" + std::to_string(batcher.batches_per_epoch()) + " loss " + format_double(value, 4) +
                 " (" + format_double(seconds_since(start), 4) + " s)");
      }
    }
    p.last_epoch_loss = p.epoch_loss_sum / double(batcher.batches_per_epoch());
    ++p.epoch;
    p.batch = 0;
    p.epoch_loss_sum = 0.0;
    checkpoint();
    log_info("epoch " + std::to_string(p.epoch) + "/" + std::to_string(o.epochs) + " done: mean CTC loss " +
             format_double(p.last_epoch_loss, 4) + " (" + format_double(seconds_since(start), 4) + " s)");
  }
  if (result.first_epoch > o.epochs) log_info(o.model_dir + ": already trained for " + std::to_string(p.epoch) + " epochs");
  result.epochs_done = p.epoch;
  result.steps_done = p.step;
  result.last_epoch_loss = p.last_epoch_loss;
  result.train_s = seconds_since(start);
  result.peak_rss_mb = peak_rss_mb();
  return result;
}

AsrDecodeResult decode_asr(const AsrDecodeOptions& o) {
  o.validate();
  const torch::Device device = torch_device_of(o.device);
  set_openblas_threads(1);
  torch::set_num_threads(o.num_threads);
  const auto start = Clock::now();
  const std::string settings_path = (fs::path(o.model_dir) / "settings.txt").string();
  const std::string checkpoint_path = (fs::path(o.model_dir) / "checkpoint.pt").string();
  run_inputs()->add(settings_path);
  run_inputs()->add(checkpoint_path);
  const AsrSettings settings = read_asr_settings(settings_path);
  const LogMelOptions features = feature_options_of(settings, settings_path);
  const AsrModelConfig config = model_config_of(settings, settings_path);
  config.validate();
  CtcModel model(config, features.num_mel_bins);
  {
    torch::serialize::InputArchive archive;
    open_checkpoint(checkpoint_path, archive, torch::kCPU);
    c10::IValue stored;
    if (!archive.try_read("settings", stored) || !stored.isString() ||
        stored.toStringRef() != asr_settings_text(settings)) {
      throw Error(checkpoint_path + ": its settings differ from " + settings_path);
    }
    load_model(archive, model, checkpoint_path);
  }
  model->to(device);
  model->eval();
  torch::NoGradGuard no_grad;

  const std::vector<AsrUtterance> utts = load_asr_utterances(o.data_dir, features, false, o.num_threads, run_inputs());
  std::vector<std::string> hyps(utts.size());
  for (size_t i = 0; i < utts.size(); i += size_t(o.batch_size)) {
    std::vector<const AsrUtterance*> batch;
    for (size_t j = i; j < std::min(utts.size(), i + size_t(o.batch_size)); ++j) batch.push_back(&utts[j]);
    torch::Tensor lengths, out_lengths;
    torch::Tensor x = make_batch(batch, &lengths, nullptr, "").to(device);
    torch::Tensor best = model->forward(x, lengths, &out_lengths).argmax(2).to(torch::kCPU).contiguous();
    for (size_t b = 0; b < batch.size(); ++b) {
      const int64_t n = out_lengths[int64_t(b)].item<int64_t>();
      const int64_t* ids = best[int64_t(b)].data_ptr<int64_t>();
      hyps[i + b] = decode_characters(ctc_collapse(std::vector<int>(ids, ids + n)));
    }
  }

  AsrDecodeResult result;
  result.num_utterances = utts.size();
  result.scored = !utts.empty() && std::any_of(utts.begin(), utts.end(), [](const AsrUtterance& u) { return !u.text.empty(); });
  // The four files appear together, or none of them (an owned output dir: io/owned_output.h).
  OwnedOutputDir out(o.out_dir);
  const auto open = [&](const std::string& name) {
    return std::ofstream((fs::path(out.path()) / name).string());
  };
  std::ofstream hyp_file = open("hyp");
  for (size_t i = 0; i < utts.size(); ++i) hyp_file << utts[i].id << (hyps[i].empty() ? "" : " ") << hyps[i] << '\n';
  bool ok = bool(hyp_file.flush());
  if (result.scored) {
    std::ofstream per_utt = open("utt_errors");
    per_utt << "# utt ref_words word_errors ins del sub ref_chars char_errors ins del sub\n";
    size_t word_sentence_errors = 0, char_sentence_errors = 0;
    for (size_t i = 0; i < utts.size(); ++i) {
      const EditCounts w = count_edits(word_tokens(utts[i].text), word_tokens(hyps[i]));
      const EditCounts c = count_edits(character_tokens(utts[i].text), character_tokens(hyps[i]));
      result.words += w;
      result.characters += c;
      word_sentence_errors += w.errors() > 0;
      char_sentence_errors += c.errors() > 0;
      per_utt << utts[i].id << ' ' << w.ref_length << ' ' << w.errors() << ' ' << w.insertions << ' ' << w.deletions
              << ' ' << w.substitutions << ' ' << c.ref_length << ' ' << c.errors() << ' ' << c.insertions << ' '
              << c.deletions << ' ' << c.substitutions << '\n';
    }
    std::ofstream wer = open("wer");
    wer << format_compute_wer(result.words, word_sentence_errors, utts.size(), 0);
    std::ofstream cer = open("cer");
    cer << format_compute_wer(result.characters, char_sentence_errors, utts.size(), 0);
    ok = ok && per_utt.flush() && wer.flush() && cer.flush();
  }
  if (!ok) throw Error("cannot write the decoding results into " + o.out_dir);
  out.commit();
  result.decode_s = seconds_since(start);
  result.peak_rss_mb = peak_rss_mb();
  return result;
}

}  // namespace tsrir
