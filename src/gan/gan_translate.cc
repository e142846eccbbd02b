// gas-to-real: runs one trained generator over a RIR set, keeping each input's id (the original's
// shuffled loader lost the input/output pairing; docs/reference/spec-digest.md §3.6).
#include <c10/core/InferenceMode.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <future>

#include "gan/gan_bfloat16.h"
#include "gan/gan_input.h"
#include "gan/gan_checkpoint.h"
#include "gan/gan_networks.h"
#include "gan/gan_runtime.h"
#include "gan/gan_tensor_allocator.h"
#include "gan/gan_settings.h"
#include "gan/ts_rirgan.h"
#include "io/rir_set.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace tsrir {

namespace {

// The generator over `rows` in passes of `batch_rows` rows (each padded with silent rows to
// batch_rows when `pad`, else as many as there are): one output of kGanSliceLength per row.
std::vector<std::vector<float>> generate_rows(gan::Generator& generator, const std::vector<const GanInput*>& rows,
                                              size_t batch_rows, bool pad, const torch::Device& device,
                                              torch::ScalarType dtype) {
  std::vector<std::vector<float>> out;
  for (size_t first = 0; first < rows.size(); first += batch_rows) {
    const size_t n = std::min(rows.size() - first, batch_rows);
    torch::Tensor x = torch::zeros({int64_t(pad ? batch_rows : n), 1, int64_t(kGanSliceLength)});
    for (size_t i = 0; i < n; ++i) {
      std::memcpy(x[i].data_ptr<float>(), rows[first + i]->samples.data(), kGanSliceLength * sizeof(float));
    }
    const torch::Tensor y =
        generator->forward(x.to(device).to(dtype)).to(torch::kCPU).to(torch::kFloat32).contiguous();
    for (size_t i = 0; i < n; ++i) {
      const float* p = y[i].data_ptr<float>();
      out.emplace_back(p, p + kGanSliceLength);
    }
  }
  return out;
}

// One translated channel: its kept length, its level restored (--restore-level), a residual or
// band-gain output brought back under full scale.
Signal output_channel(const std::vector<float>& out, const GanInput& in, const std::string& id,
                      const GanTranslateOptions& o, const GanSettings& settings) {
  Signal rir;
  rir.id = id;
  rir.sample_rate_hz = kGanSampleRateHz;
  const size_t length = o.keep_length < 0 ? in.length : size_t(o.keep_length);
  float scale = o.restore_level ? float(in.peak) : 1.0f;
  if (settings.generator != GanGenerator::kOriginal) {
    // A residual or band-gain output is its peak-normalised input plus what the generator
    // added, so its peak can pass 1: scale it back to the largest 16-bit value (32767/32768), the training data's peak.
    constexpr float kFullScale = 32767.0f / 32768.0f;
    float peak = 0.0f;
    for (size_t k = 0; k < length; ++k) peak = std::max(peak, std::abs(out[k]));
    if (peak > kFullScale) scale *= kFullScale / peak;
  }
  rir.samples.resize(length);
  for (size_t k = 0; k < length; ++k) rir.samples[k] = out[k] * scale;
  return rir;
}

}  // namespace

GanTranslateResult translate_rirs(const GanTranslateOptions& o) {
  if (o.batch_size < 1) throw Error("--batch-size must be >= 1");
  if (o.num_threads < 1) throw Error("--num-threads must be >= 1");
  if (o.keep_length != -1 && (o.keep_length < 1 || o.keep_length > (long long)kGanSliceLength)) {
    throw Error("--keep-length must be 'input' or in [1, 16384], got " + std::to_string(o.keep_length));
  }
  const std::string network = o.direction == GanDirection::kSyntheticToReal ? "g_real" : "g_synthetic";
  if (o.precision == GanPrecision::kBfloat16) require_float32_sums_for_bfloat16("gas-to-real");
  const torch::ScalarType dtype = o.precision == GanPrecision::kBfloat16 ? torch::kBFloat16 : torch::kFloat32;
  tune_memory_for_torch();
  set_openblas_threads(1);
  gan::set_torch_threads(o.num_threads);
  const torch::Device device = gan::torch_device(o.device);

  std::string checkpoint = o.model;
  if (fs::is_directory(o.model)) checkpoint = (fs::path(o.model) / "checkpoint.pt").string();
  if (!fs::exists(checkpoint)) throw Error("no TS-RIRGAN checkpoint at " + checkpoint);
  // Read the input list first: a bad list should fail before a slow model load.
  const std::vector<RirRef> refs = read_rir_refs(o.input_list, run_inputs());
  if (refs.empty()) throw Error(o.input_list + ": no RIRs to translate");

  using Clock = std::chrono::steady_clock;
  GanTranslateResult result;
  auto t0 = Clock::now();
  GanSettings settings;
  long long step = 0;
  const gan::GeneratorWeights weights =
      o.use_last_weights ? gan::GeneratorWeights::kLast : gan::GeneratorWeights::kAverageWhereKept;
  std::string read_from;
  gan::Generator generator = gan::load_generator(checkpoint, network, weights, &settings, &step, &read_from);
  const std::string dir_settings = (fs::path(checkpoint).parent_path() / "settings.txt").string();
  if (fs::exists(dir_settings)) {
    check_same_architecture(read_gan_settings_file(dir_settings), settings, checkpoint + " vs " + dir_settings);
  }
  generator->to(device);
  generator->to(dtype);
  generator->eval();
  drop_kept_tensor_memory();  // where the checkpoint was read: its other networks and optimiser state
  result.model_load_s = std::chrono::duration<double>(Clock::now() - t0).count();
  const bool averaged = !o.use_last_weights && settings.generator_average_decay > 0;
  log_info("loaded " + network + " (width " + std::to_string(settings.width) + ", step " + std::to_string(step) +
           (averaged ? ", weights averaged over the steps, decay " + format_double(settings.generator_average_decay, 6)
                     : std::string(", the last step's weights")) +
           ") from " + read_from);

  t0 = Clock::now();
  auto last_progress = t0;
  RirSetWriter writer(o.out_dir, o.format);
  AudioReadOptions read_options;
  read_options.target_rate_hz = kGanSampleRateHz;
  size_t cropped = 0;
  c10::InferenceMode inference;
  // The RIRs in groups of one size, at most --batch-size: 170 at 32 are 6 groups of 29 (the last
  // holds 25 and is padded with 4 silent rows), not 5 of 32 and one of 10 padded with 22 (a padding
  // row costs as much as a real one).
  const size_t groups = (refs.size() + size_t(o.batch_size) - 1) / size_t(o.batch_size);
  const size_t group_size = (refs.size() + groups - 1) / groups;
  // Every channel of a multichannel RIR (a microphone array's) is a row of its own.
  auto load_group = [&](size_t begin) {
    std::vector<std::vector<GanInput>> inputs(std::min(refs.size() - begin, group_size));
    parallel_for(inputs.size(), o.num_threads, [&](size_t i) {
      for (const Signal& channel : load_rir_channels(refs[begin + i], read_options)) {
        inputs[i].push_back(prepare_gan_input(channel));
      }
    });
    return inputs;
  };
  // The next group is read while the generator runs on this one.
  std::future<std::vector<std::vector<GanInput>>> next_group = std::async(std::launch::async, load_group, 0);
  for (size_t begin = 0; begin < refs.size(); begin += group_size) {
    const std::vector<std::vector<GanInput>> inputs = next_group.get();
    const size_t n = inputs.size();
    if (begin + n < refs.size()) next_group = std::async(std::launch::async, load_group, begin + n);
    std::vector<const GanInput*> rows;
    for (const auto& channels : inputs) {
      for (const GanInput& in : channels) {
        rows.push_back(&in);
        cropped += in.cropped;
      }
    }
    // A short pass (the last group's, or a multichannel group's last) is padded with silent rows
    // to the group size: a new input shape makes oneDNN create (JIT-compile) every layer's kernels
    // again. Rows do not interact (no batch statistics in the generator).
    const bool pad = groups > 1 || rows.size() > group_size;
    const std::vector<std::vector<float>> outputs = generate_rows(generator, rows, group_size, pad, device, dtype);
    size_t row = 0;
    for (size_t i = 0; i < n; ++i) {
      std::vector<Signal> channels;
      for (const GanInput& in : inputs[i]) {
        channels.push_back(output_channel(outputs[row++], in, refs[begin + i].id, o, settings));
      }
      writer.add_channels(channels, refs[begin + i].room_id);
    }
    result.num_rirs += n;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_progress).count() > 10.0) {
      last_progress = now;
      log_info("translated " + std::to_string(result.num_rirs) + "/" + std::to_string(refs.size()));
    }
  }
  if (cropped > 0) {
    log_warning(o.input_list + ": " + std::to_string(cropped) + " of " + std::to_string(refs.size()) +
                " RIRs are longer than 16384 samples at 16 kHz; only their first 16384 samples were " +
                "translated (as the original)");
  }
  writer.commit();
  result.translate_s = std::chrono::duration<double>(Clock::now() - t0).count();
  result.peak_rss_mb = peak_rss_mb();
  return result;
}

}  // namespace tsrir
