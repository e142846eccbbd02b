// The simulation model as an ordered set of composable components.
//
// A Model renders one RIR in three stages; each component works in exactly one of them:
//   kRoom       adjust_room(RoomSpec&)            changes the set-up before rendering
//                                                 (e.g. a per-band absorption or scattering refit)
//   kBands      render_bands(ctx, BandSignals&)   adds to / transforms the 8 octave-band signals,
//                                                 before they are band-filtered and summed
//                                                 (image sources, diffuse tail, air absorption)
//   kBroadband  process_rir(ctx, samples)         transforms the summed broadband RIR
//                                                 (room modes crossover, transducer response,
//                                                 onset shift, noise floor)
// Within a stage, components run in ascending order() (ties: by name), never in the order the
// user wrote them, so "gas+air" and "air+gas" are the same model. Orders in use:
//   kBands: ism 100, directivity 150, diffuse 200 (reads what ism left in RenderContext::facts);
//           suggested: air absorption 300.
//   kBroadband: suggested modes 100, transducer 200, onset shift 300, noise floor 400.
// Components are immutable after construction and shared by all threads: render hooks are const
// and draw randomness only from ctx.rng_for(name()), a stream keyed by (seed, rir id, component
// name), so adding a component never changes another component's draws.
//
// How to add a component (e.g. "air"):
//   1. In a new file (src/sim/air_absorption.{h,cc}, or your own area), derive from ModelComponent:
//      implement name(), stage(), order() and the hook of that stage. Read parameters in the
//      constructor from ComponentParams (params.number("key", default)); Model::parse() rejects
//      any parameter the constructor did not ask for.
//   2. Register a factory: add one register_builtin(...) line to register_builtin_components() in
//      src/sim/components.cc, or call register_model_component() from your own library before
//      the first Model::parse() (e.g. at the start of your program's main). Aliases
//      (register_model_alias("gas", "ism+diffuse")) name combinations. (No static-initialiser
//      self-registration: the linker drops unreferenced objects of static libraries.)
//   3. Users write --model=gas+air or gas+air:humidity_scale=1.2 (parameters after ':',
//      comma-separated key=value).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/signal.h"
#include "sim/room.h"
#include "util/rng.h"

namespace tsrir::sim {

enum class ModelStage { kRoom = 0, kBands = 1, kBroadband = 2 };

// Per-octave-band time signals, each num_samples long at the model's rate. The model sums them
// through complementary zero-phase octave filters (sum of the filters = 1 at every frequency, so
// a component that adds the same signal to every band adds it unfiltered to the RIR).
struct BandSignals {
  std::array<std::vector<float>, kNumOctaveBands> band;
};

// Facts one component leaves for later ones in the same render.
struct RenderFacts {
  double direct_delay_s = 0.0;       // set by the Model: distance / c
  // Set by "ism": image sources cover [0, transition_time_s); 0 = no image sources rendered.
  double transition_time_s = 0.0;
  // Set by "ism": energy (sum of squared amplitudes) of image arrivals in
  // [window_start_s, transition_time_s) per band, before the scattering loss, and what the
  // statistical (Eyring) diffuse field predicts for the same window; their ratio calibrates the
  // diffuse level so that the energy is continuous at the transition.
  double window_start_s = 0.0;
  BandValues window_image_energy{};
  BandValues window_diffuse_energy{};
  // Free-form facts for components added later (key: "<component>.<name>"), so a new component
  // can pass values to another without changing this struct.
  std::map<std::string, double> values;
  std::map<std::string, BandValues> band_values;
};

struct RenderContext {
  const RoomSpec& room;             // after the kRoom stage
  double sample_rate_hz;
  size_t num_samples;
  uint64_t seed;
  mutable RenderFacts facts;
  // Which microphone of an array this context renders (room.mic_m is its position); 0 for a single
  // microphone.
  size_t mic_index = 0;
  // A random stream for one component in this render (independent of threads and order); each
  // microphone of an array has its own (microphone 0's is the single-microphone stream).
  Rng rng_for(const std::string& component_name) const;
};

// key=value parameters of one component in a model string; numbers are checked when read.
class ComponentParams {
 public:
  ComponentParams(std::string component, std::map<std::string, std::string> values);
  double number(const std::string& key, double default_value);
  std::string text(const std::string& key, const std::string& default_value);
  bool has(const std::string& key) const { return values_.count(key) > 0; }
  // Throws Error if a parameter was given that no number()/text() call asked for (Model::parse
  // calls it after the factory).
  void finish() const;
  const std::string& component() const { return component_; }

 private:
  std::string component_;
  std::map<std::string, std::string> values_;
  std::map<std::string, bool> used_;
};

class ModelComponent {
 public:
  virtual ~ModelComponent() = default;
  virtual std::string name() const = 0;
  virtual ModelStage stage() const = 0;
  virtual int order() const = 0;
  // The longest decay this component can produce per band, for --length=auto (0 = none).
  virtual double max_decay_time_s(const RoomSpec& room) const;

  virtual void adjust_room(RoomSpec& room) const;
  virtual void render_bands(const RenderContext& ctx, BandSignals& bands) const;
  // The kBands stage for every microphone of an array at once (ctxs[m] renders into *bands[m]).
  // The default renders each microphone alone; components that share work across the array (ism:
  // the image lattice) or couple the microphones (diffuse: the spatial coherence of the tail)
  // override it.
  virtual void render_array_bands(const std::vector<const RenderContext*>& ctxs,
                                  const std::vector<BandSignals*>& bands) const;
  virtual void process_rir(const RenderContext& ctx, std::vector<float>& samples) const;
};

using ComponentFactory = std::function<std::unique_ptr<ModelComponent>(ComponentParams&)>;

// Registry (process-wide, thread-safe). Registering an existing name replaces it.
void register_model_component(const std::string& name, const std::string& description,
                              ComponentFactory factory);
void register_model_alias(const std::string& alias, const std::string& expansion);
// "name - description" lines and "alias = expansion" lines, for --help.
std::string model_components_help();

class Model {
 public:
  // Parses "gas", "gas+air", "ism:max_images=4000+diffuse", ... (aliases expanded). Throws Error
  // for unknown components/parameters or a component given twice.
  static Model parse(const std::string& spec);

  const std::string& spec() const { return spec_; }
  std::vector<std::string> component_names() const;  // in evaluation order
  bool has_component(const std::string& name) const;

  // The kRoom stage applied to a copy of `room` (validated again afterwards).
  RoomSpec prepare_room(const RoomSpec& room) const;
  // Length for --length=auto: direct delay + the longest decay of any component (>= 0.1 s).
  double auto_length_s(const RoomSpec& prepared_room) const;
  // Renders one RIR of num_samples at sample_rate_hz; deterministic in (seed, room.rir_id).
  // The result's id is room.rir_id.
  Signal render(const RoomSpec& room, double sample_rate_hz, size_t num_samples, uint64_t seed) const;
  // Every microphone of room's array (room.num_mics() signals, in array order, each with id
  // room.rir_id); for one microphone the same samples as render().
  std::vector<Signal> render_array(const RoomSpec& room, double sample_rate_hz, size_t num_samples,
                                   uint64_t seed) const;
  // The kBands stage only (before band filtering), for analysis and fitting.
  BandSignals render_band_signals(const RoomSpec& prepared_room, double sample_rate_hz,
                                  size_t num_samples, uint64_t seed, RenderFacts* facts = nullptr) const;

 private:
  std::string spec_;
  std::vector<std::shared_ptr<const ModelComponent>> components_;  // evaluation order
};

// Sums band signals through the complementary octave filters (FFT engine of src/dsp).
std::vector<float> combine_octave_bands(const BandSignals& bands, double sample_rate_hz);

}  // namespace tsrir::sim
