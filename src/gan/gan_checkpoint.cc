#include "gan/gan_checkpoint.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <tuple>

#include "io/atomic_output.h"
#include "util/error.h"
#include "util/log.h"
#include "util/zip_fingerprint.h"

namespace fs = std::filesystem;

namespace tsrir {
namespace gan {
namespace {

constexpr const char* kCheckpointTag = "tsrir-ts-rirgan-checkpoint-v1";
constexpr const char* kGeneratorFileTag = "tsrir-ts-rirgan-generator-v1";

std::string archive_key(const std::string& network, const std::string& parameter) {
  std::string key = network + "__" + parameter;
  std::replace(key.begin(), key.end(), '.', '_');
  return key;
}

struct NamedNetwork {
  std::string name;
  torch::nn::Module* module;
  TfRmsProp* optimizer;
};

// What a checkpoint holds: the four networks with their optimiser state, then the generators'
// weight averages where the model keeps them (no optimiser).
std::vector<NamedNetwork> networks_of(CycleGan& model) {
  std::vector<NamedNetwork> networks = {{"g_real", model.g_real.get(), &model.optimizers[0]},
                                        {"g_synthetic", model.g_synthetic.get(), &model.optimizers[1]},
                                        {"d_real", model.d_real.get(), &model.optimizers[2]},
                                        {"d_synthetic", model.d_synthetic.get(), &model.optimizers[3]}};
  if (model.g_real_average) {
    networks.push_back({"g_real_average", model.g_real_average.get(), nullptr});
    networks.push_back({"g_synthetic_average", model.g_synthetic_average.get(), nullptr});
  }
  return networks;
}

void open_archive(const std::string& path, torch::serialize::InputArchive& archive,
                  const char* tag_wanted = kCheckpointTag) {
  try {
    archive.load_from(path, torch::kCPU);
  } catch (const std::exception& e) {
    std::string why = e.what();
    why = why.substr(0, why.find('\n'));
    throw Error(path + ": not a readable TS-RIRGAN checkpoint (" + why + ")");
  }
  c10::IValue tag;
  if (!archive.try_read("format", tag) || !tag.isString() || tag.toStringRef() != tag_wanted) {
    throw Error(path + ": not a TS-RIRGAN " + (tag_wanted == kCheckpointTag ? "checkpoint" : "generator file") +
                " (no '" + std::string(tag_wanted) + "' tag)");
  }
}

GanSettings archive_settings(torch::serialize::InputArchive& archive, const std::string& path) {
  c10::IValue text;
  if (!archive.try_read("settings", text) || !text.isString()) {
    throw Error(path + ": has no settings");
  }
  return parse_gan_settings(text.toStringRef(), path + " (settings)");
}

long long archive_step(torch::serialize::InputArchive& archive, const std::string& path) {
  torch::Tensor step;
  if (!archive.try_read("step", step) || step.numel() != 1) throw Error(path + ": has no step");
  return step.item<int64_t>();
}

// The stored tensor under `key`, checked against the model's `target` (torch's own read() would
// silently take any shape, and copy_() any type).
torch::Tensor checked_stored(torch::serialize::InputArchive& archive, const std::string& key,
                             const torch::Tensor& target, const std::string& path) {
  torch::Tensor stored;
  if (!archive.try_read(key, stored)) throw Error(path + ": lacks tensor '" + key + "'");
  if (stored.sizes() != target.sizes() || stored.scalar_type() != target.scalar_type()) {
    std::ostringstream os;
    os << path << ": tensor '" << key << "' is " << stored.scalar_type() << " " << stored.sizes()
       << ", the model expects " << target.scalar_type() << " " << target.sizes();
    throw Error(os.str());
  }
  return stored;
}

// Copies into `target`: for tensors whose memory others already hold (optimiser state, modules
// built by the trainer).
void read_into(torch::serialize::InputArchive& archive, const std::string& key, torch::Tensor& target,
               const std::string& path) {
  torch::Tensor stored = checked_stored(archive, key, target, path);
  torch::NoGradGuard no_grad;
  target.copy_(stored);
}

// The stored weights `weights` asks for: the moving average's name where the model keeps one.
std::string stored_name(const std::string& name, GeneratorWeights weights, const GanSettings& settings) {
  const bool average = weights == GeneratorWeights::kAverageWhereKept && settings.generator_average_decay > 0;
  return average ? name + "_average" : name;
}

void write_archive(torch::serialize::OutputArchive& archive, const std::string& path, const char* what) {
  const std::string temp = make_temp_path(path);
  try {
    archive.save_to(temp);
  } catch (const std::exception& e) {
    discard_temp_path(temp);
    throw Error(std::string("cannot write ") + what + " " + path + ": " + std::string(e.what()).substr(0, 200));
  }
  commit_temp_path(temp, path);
}

// A fresh generator whose parameters take the stored tensors' memory (nothing else holds a
// loaded generator's parameters; saves writing, and first touching, 166 MB at width 64).
Generator generator_from_archive(torch::serialize::InputArchive& archive, const GanSettings& settings,
                                 const std::string& stored, const std::string& path) {
  Generator generator = make_generator(settings, GanInit::kLoaded);
  torch::NoGradGuard no_grad;
  for (auto& item : generator->named_parameters()) {
    item.value().set_data(checked_stored(archive, archive_key(stored, item.key()), item.value(), path).contiguous());
  }
  return generator;
}

// The generator from the file beside the checkpoint, or nothing when it is absent, holds other
// weights than those asked for, or was written for another checkpoint (*why says which; an
// unreadable file too: it is derived from the checkpoint, which can still be read).
Generator read_generator_file(const std::string& checkpoint, const std::string& name, GeneratorWeights weights,
                              GanSettings* settings, long long* step, std::string* why) {
  const std::string path = generator_file_path(checkpoint, name);
  if (!fs::exists(path)) return nullptr;
  torch::serialize::InputArchive archive;
  open_archive(path, archive, kGeneratorFileTag);
  c10::IValue fingerprint, stored;
  if (!archive.try_read("checkpoint_fingerprint", fingerprint) || !fingerprint.isString() ||
      !archive.try_read("weights", stored) || !stored.isString()) {
    throw Error(path + ": generator file without its checkpoint's fingerprint or weights name");
  }
  if (fingerprint.toStringRef() != zip_fingerprint(checkpoint)) {
    *why = path + " was written for another checkpoint than " + checkpoint + "; reading the checkpoint (slower)";
    return nullptr;
  }
  const GanSettings file_settings = archive_settings(archive, path);
  if (stored.toStringRef() != stored_name(name, weights, file_settings)) return nullptr;  // e.g. --use-last-weights
  Generator generator = generator_from_archive(archive, file_settings, stored.toStringRef(), path);
  *settings = file_settings;
  *step = archive_step(archive, path);
  return generator;
}

}  // namespace

void save_checkpoint(const std::string& path, const CycleGan& model, long long step) {
  torch::serialize::OutputArchive archive;
  archive.write("format", c10::IValue(std::string(kCheckpointTag)));
  archive.write("settings", c10::IValue(gan_settings_text(model.settings)));
  archive.write("step", torch::tensor(static_cast<int64_t>(step)));
  // The networks are only read here; networks_of() serves both directions.
  for (const auto& net : networks_of(const_cast<CycleGan&>(model))) {
    for (const auto& item : net.module->named_parameters()) {
      archive.write(archive_key(net.name, item.key()), item.value().detach().cpu());
    }
    if (!net.optimizer) continue;
    const auto& ms = net.optimizer->mean_square();
    for (size_t i = 0; i < ms.size(); ++i) {
      archive.write(archive_key(net.name + "__rms", std::to_string(i)), ms[i].cpu());
    }
  }
  write_archive(archive, path, "checkpoint");
}

long long load_checkpoint(const std::string& path, CycleGan& model) {
  torch::serialize::InputArchive archive;
  open_archive(path, archive);
  check_same_architecture(model.settings, archive_settings(archive, path), path);
  for (const auto& net : networks_of(model)) {
    for (auto& item : net.module->named_parameters()) {
      read_into(archive, archive_key(net.name, item.key()), item.value(), path);
    }
    if (!net.optimizer) continue;
    auto& ms = net.optimizer->mean_square();
    for (size_t i = 0; i < ms.size(); ++i) {
      read_into(archive, archive_key(net.name + "__rms", std::to_string(i)), ms[i], path);
    }
  }
  return archive_step(archive, path);
}

GanSettings read_checkpoint_settings(const std::string& path) {
  torch::serialize::InputArchive archive;
  open_archive(path, archive);
  return archive_settings(archive, path);
}

std::string generator_file_path(const std::string& checkpoint_path, const std::string& name) {
  return (fs::path(checkpoint_path).parent_path() / ("generator-" + name + ".pt")).string();
}

void save_generator_files(const std::string& checkpoint_path, const CycleGan& model, long long step) {
  const std::string fingerprint = zip_fingerprint(checkpoint_path);
  for (const auto& [name, live, average] : {std::tuple{"g_real", model.g_real, model.g_real_average},
                                            std::tuple{"g_synthetic", model.g_synthetic, model.g_synthetic_average}}) {
    const std::string stored = stored_name(name, GeneratorWeights::kAverageWhereKept, model.settings);
    const Generator& generator = average ? average : live;
    torch::serialize::OutputArchive archive;
    archive.write("format", c10::IValue(std::string(kGeneratorFileTag)));
    archive.write("settings", c10::IValue(gan_settings_text(model.settings)));
    archive.write("step", torch::tensor(static_cast<int64_t>(step)));
    archive.write("weights", c10::IValue(stored));
    archive.write("checkpoint_fingerprint", c10::IValue(fingerprint));
    for (const auto& item : generator->named_parameters()) {
      archive.write(archive_key(stored, item.key()), item.value().detach().cpu());
    }
    write_archive(archive, generator_file_path(checkpoint_path, name), "generator file");
  }
}

Generator load_generator(const std::string& path, const std::string& name, GeneratorWeights weights,
                         GanSettings* settings, long long* step, std::string* read_from) {
  std::string why;
  Generator from_file{nullptr};
  try {
    from_file = read_generator_file(path, name, weights, settings, step, &why);
  } catch (const std::exception& e) {
    why = std::string(e.what()) + "; reading the checkpoint instead";
  }
  if (from_file) {
    if (read_from) *read_from = generator_file_path(path, name);
    return from_file;
  }
  if (!why.empty()) log_warning(why);
  torch::serialize::InputArchive archive;
  open_archive(path, archive);
  *settings = archive_settings(archive, path);
  Generator generator = generator_from_archive(archive, *settings, stored_name(name, weights, *settings), path);
  *step = archive_step(archive, path);
  if (read_from) *read_from = path;
  return generator;
}

}  // namespace gan
}  // namespace tsrir
