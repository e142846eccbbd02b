#include "sim/model.h"
#include "sim/builtin_components.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <set>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir::sim {

namespace {

struct RegistryEntry {
  std::string description;
  ComponentFactory factory;
};

struct Registry {
  std::mutex mutex;
  std::map<std::string, RegistryEntry> components;
  std::map<std::string, std::string> aliases;
};

Registry& raw_registry() {
  static Registry registry;
  return registry;
}

// Built-ins are registered on first use, before any user registration can be overwritten by them.
Registry& registry() {
  static std::once_flag once;
  std::call_once(once, [] { register_builtin_components(); });
  return raw_registry();
}

struct ParsedComponent {
  std::string name;
  std::map<std::string, std::string> params;
};

void parse_into(const std::string& spec, const std::string& whole, int depth,
                std::vector<ParsedComponent>* out) {
  if (depth > 8) throw Error("model '" + whole + "': aliases nest too deeply");
  Registry& reg = registry();
  for (const std::string& piece_raw : split(spec, '+')) {
    const std::string piece = trim(piece_raw);
    if (piece.empty()) throw Error("model '" + whole + "': empty component name");
    const size_t colon = piece.find(':');
    const std::string name = trim(piece.substr(0, colon));
    std::map<std::string, std::string> params;
    if (colon != std::string::npos) {
      for (const std::string& kv : split(piece.substr(colon + 1), ',')) {
        const size_t eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) {
          throw Error("model '" + whole + "': component parameter '" + kv + "' is not key=value");
        }
        if (!params.emplace(trim(kv.substr(0, eq)), trim(kv.substr(eq + 1))).second) {
          throw Error("model '" + whole + "': parameter '" + kv.substr(0, eq) + "' given twice");
        }
      }
    }
    std::string expansion;
    {
      std::lock_guard<std::mutex> lock(reg.mutex);
      auto alias = reg.aliases.find(name);
      if (alias != reg.aliases.end()) {
        expansion = alias->second;
      } else if (!reg.components.count(name)) {
        std::string known;
        for (const auto& c : reg.components) known += " " + c.first;
        for (const auto& a : reg.aliases) known += " " + a.first;
        throw Error("model '" + whole + "': unknown component '" + name + "' (known:" + known + ")");
      }
    }
    if (!expansion.empty()) {
      if (!params.empty()) {
        throw Error("model '" + whole + "': '" + name + "' is an alias for '" + expansion +
                    "'; give parameters to its components instead");
      }
      parse_into(expansion, whole, depth + 1, out);
    } else {
      out->push_back({name, std::move(params)});
    }
  }
}

}  // namespace

Rng RenderContext::rng_for(const std::string& component_name) const {
  const std::string mic = mic_index == 0 ? std::string() : "\x1fmic" + std::to_string(mic_index);
  return Rng::for_item(seed, room.rir_id + '\x1f' + component_name + mic);
}

ComponentParams::ComponentParams(std::string component, std::map<std::string, std::string> values)
    : component_(std::move(component)), values_(std::move(values)) {}

double ComponentParams::number(const std::string& key, double default_value) {
  used_[key] = true;
  auto it = values_.find(key);
  if (it == values_.end()) return default_value;
  return parse_double(it->second, "model component " + component_ + ": " + key);
}

std::string ComponentParams::text(const std::string& key, const std::string& default_value) {
  used_[key] = true;
  auto it = values_.find(key);
  return it == values_.end() ? default_value : it->second;
}

void ComponentParams::finish() const {
  for (const auto& kv : values_) {
    if (!used_.count(kv.first)) {
      std::string known;
      for (const auto& u : used_) known += " " + u.first;
      throw Error("model component " + component_ + ": unknown parameter '" + kv.first + "'" +
                  (known.empty() ? std::string(" (it takes none)") : " (known:" + known + ")"));
    }
  }
}

double ModelComponent::max_decay_time_s(const RoomSpec&) const { return 0.0; }
void ModelComponent::adjust_room(RoomSpec&) const {}
void ModelComponent::render_bands(const RenderContext&, BandSignals&) const {}
void ModelComponent::process_rir(const RenderContext&, std::vector<float>&) const {}
void ModelComponent::render_array_bands(const std::vector<const RenderContext*>& ctxs,
                                        const std::vector<BandSignals*>& bands) const {
  for (size_t m = 0; m < ctxs.size(); ++m) render_bands(*ctxs[m], *bands[m]);
}

void register_model_component(const std::string& name, const std::string& description,
                              ComponentFactory factory) {
  if (name.empty() || name.find_first_of("+:,= \t") != std::string::npos) {
    throw Error("invalid model component name '" + name + "'");
  }
  Registry& reg = registry();
  std::lock_guard<std::mutex> lock(reg.mutex);
  reg.aliases.erase(name);
  reg.components[name] = {description, std::move(factory)};
}

void register_model_alias(const std::string& alias, const std::string& expansion) {
  Registry& reg = registry();
  std::lock_guard<std::mutex> lock(reg.mutex);
  reg.components.erase(alias);
  reg.aliases[alias] = expansion;
}

// Built-in registration goes straight to the raw registry (registry() is still initialising).
void register_builtin(const std::string& name, const std::string& description, ComponentFactory factory) {
  raw_registry().components[name] = {description, std::move(factory)};
}
void register_builtin_alias(const std::string& alias, const std::string& expansion) {
  raw_registry().aliases[alias] = expansion;
}

std::string model_components_help() {
  Registry& reg = registry();
  std::lock_guard<std::mutex> lock(reg.mutex);
  std::string out;
  for (const auto& a : reg.aliases) out += "  " + a.first + " = " + a.second + "\n";
  for (const auto& c : reg.components) out += "  " + c.first + ": " + c.second.description + "\n";
  return out;
}

Model Model::parse(const std::string& spec) {
  std::vector<ParsedComponent> parsed;
  parse_into(spec, spec, 0, &parsed);
  Model model;
  model.spec_ = spec;
  std::set<std::string> names;
  for (ParsedComponent& pc : parsed) {
    if (!names.insert(pc.name).second) {
      throw Error("model '" + spec + "': component '" + pc.name + "' appears twice");
    }
    ComponentFactory factory;
    {
      Registry& reg = registry();
      std::lock_guard<std::mutex> lock(reg.mutex);
      factory = reg.components.at(pc.name).factory;
    }
    ComponentParams params(pc.name, pc.params);
    std::unique_ptr<ModelComponent> component = factory(params);
    params.finish();
    model.components_.push_back(std::move(component));
  }
  std::stable_sort(model.components_.begin(), model.components_.end(),
                   [](const auto& a, const auto& b) {
                     if (a->stage() != b->stage()) return a->stage() < b->stage();
                     if (a->order() != b->order()) return a->order() < b->order();
                     return a->name() < b->name();
                   });
  return model;
}

std::vector<std::string> Model::component_names() const {
  std::vector<std::string> names;
  for (const auto& c : components_) names.push_back(c->name());
  return names;
}

bool Model::has_component(const std::string& name) const {
  for (const auto& c : components_) {
    if (c->name() == name) return true;
  }
  return false;
}

RoomSpec Model::prepare_room(const RoomSpec& room) const {
  RoomSpec prepared = room;
  for (const auto& c : components_) {
    if (c->stage() == ModelStage::kRoom) c->adjust_room(prepared);
  }
  validate_room(prepared);
  return prepared;
}

double Model::auto_length_s(const RoomSpec& prepared_room) const {
  double decay_s = 0.0;
  for (const auto& c : components_) decay_s = std::max(decay_s, c->max_decay_time_s(prepared_room));
  double distance_m = 0.0;  // to the farthest microphone of an array
  for (size_t m = 0; m < prepared_room.num_mics(); ++m) {
    distance_m = std::max(distance_m, prepared_room.for_mic(m).source_mic_distance_m());
  }
  const double length_s = distance_m / prepared_room.speed_of_sound_m_s + decay_s;
  // Whole 10 ms steps, so lengths are readable and stable under rounding.
  return std::max(0.1, std::ceil(length_s * 100.0 - 1e-9) / 100.0);
}

BandSignals Model::render_band_signals(const RoomSpec& prepared_room, double sample_rate_hz,
                                       size_t num_samples, uint64_t seed, RenderFacts* facts) const {
  RenderContext ctx{prepared_room, sample_rate_hz, num_samples, seed, {}};
  ctx.facts.direct_delay_s = prepared_room.source_mic_distance_m() / prepared_room.speed_of_sound_m_s;
  BandSignals bands;
  for (auto& b : bands.band) b.assign(num_samples, 0.0f);
  for (const auto& c : components_) {
    if (c->stage() == ModelStage::kBands) c->render_bands(ctx, bands);
  }
  if (facts) *facts = ctx.facts;
  return bands;
}

std::vector<Signal> Model::render_array(const RoomSpec& room, double sample_rate_hz, size_t num_samples,
                                       uint64_t seed) const {
  if (!(sample_rate_hz > 0.0) || num_samples == 0) {
    throw Error("simulate: need a positive sample rate and length");
  }
  const RoomSpec prepared = prepare_room(room);
  const size_t num_mics = prepared.num_mics();
  std::vector<RoomSpec> mic_rooms;
  for (size_t m = 0; m < num_mics; ++m) mic_rooms.push_back(prepared.for_mic(m));
  std::vector<RenderContext> contexts;
  contexts.reserve(num_mics);
  std::vector<BandSignals> bands(num_mics);
  std::vector<const RenderContext*> context_ptrs;
  std::vector<BandSignals*> band_ptrs;
  for (size_t m = 0; m < num_mics; ++m) {
    contexts.push_back(RenderContext{mic_rooms[m], sample_rate_hz, num_samples, seed, {}, m});
    contexts[m].facts.direct_delay_s = mic_rooms[m].source_mic_distance_m() / mic_rooms[m].speed_of_sound_m_s;
    for (auto& b : bands[m].band) b.assign(num_samples, 0.0f);
    context_ptrs.push_back(&contexts[m]);
    band_ptrs.push_back(&bands[m]);
  }
  for (const auto& c : components_) {
    if (c->stage() == ModelStage::kBands) c->render_array_bands(context_ptrs, band_ptrs);
  }
  std::vector<Signal> out(num_mics);
  for (size_t m = 0; m < num_mics; ++m) {
    out[m].id = room.rir_id;
    out[m].sample_rate_hz = sample_rate_hz;
    out[m].samples = combine_octave_bands(bands[m], sample_rate_hz);
    for (const auto& c : components_) {
      if (c->stage() == ModelStage::kBroadband) c->process_rir(contexts[m], out[m].samples);
    }
    if (out[m].samples.size() != num_samples) {
      throw Error("simulate: a model component changed the RIR length");
    }
  }
  return out;
}

Signal Model::render(const RoomSpec& room, double sample_rate_hz, size_t num_samples, uint64_t seed) const {
  if (room.num_mics() != 1) {
    throw Error(room.where + ": " + std::to_string(room.num_mics()) +
                " microphones (an array): this takes one microphone per room-list line (rir-simulate takes arrays)");
  }
  return std::move(render_array(room, sample_rate_hz, num_samples, seed).front());
}

}  // namespace tsrir::sim
