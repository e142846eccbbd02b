#include "augmenter_options.h"

#include <pybind11/stl.h>

#include <functional>
#include <map>

#include "util/error.h"

namespace tsrir::python {
namespace {

namespace py = pybind11;
using Options = ReverberateDataOptions;

struct Field {
  std::function<void(Options&, const py::handle&)> set;
  std::function<py::object(const Options&)> get;
};

template <typename T>
Field field(T Options::*member) {
  return {[member](Options& o, const py::handle& v) { o.*member = v.cast<T>(); },
          [member](const Options& o) { return py::cast(o.*member); }};
}

// A typed choice, named as on the command line (the option's own Choices table).
template <typename E>
Field choice_field(E Options::*member, const Choices<E>& choices) {
  return {[member, &choices](Options& o, const py::handle& v) { o.*member = choice_value(choices, v.cast<std::string>()); },
          [member, &choices](const Options& o) { return py::cast(choice_name(choices, o.*member)); }};
}

// The per-recording output rules live in ReverbOptions (options.reverb).
template <typename T>
Field reverb_field(T ReverbOptions::*member) {
  return {[member](Options& o, const py::handle& v) { o.reverb.*member = v.cast<T>(); },
          [member](const Options& o) { return py::cast(o.reverb.*member); }};
}

const std::map<std::string, Field>& fields() {
  static const std::map<std::string, Field> table = [] {
    std::map<std::string, Field> t;
    t["rir_set_parameters"] = field(&Options::rir_set_parameters);
    t["noise_set_parameters"] = field(&Options::noise_set_parameters);
    t["prefix"] = field(&Options::prefix);
    t["speech_rvb_probability"] = field(&Options::speech_rvb_probability);
    t["noise_start"] = choice_field(&Options::noise_start, noise_start_choices());
    t["shift_output"] = reverb_field(&ReverbOptions::shift_output);
    t["normalize_output"] = reverb_field(&ReverbOptions::normalize_output);
    t["multi_channel_output"] = field(&Options::multi_channel_output);
    t["split_channels"] = field(&Options::split_channels);
    t["rir_smoothing_weight"] = field(&Options::rir_smoothing_weight);
    t["noise_smoothing_weight"] = field(&Options::noise_smoothing_weight);
    t["seed"] = field(&Options::random_seed);
    t["sample_rate"] = field(&Options::source_sampling_rate_hz);  // --sample-rate (rate_policy.h)
    t["snr_reference"] = {
        [](Options& o, const py::handle& v) { o.reverb.snr_reference = parse_snr_reference(v.cast<std::string>()); },
        [](const Options& o) { return py::cast(snr_reference_name(o.reverb.snr_reference)); }};
    t["foreground_snrs"] = field(&Options::foreground_snrs);
    t["background_snrs"] = field(&Options::background_snrs);
    t["isotropic_noise_addition_probability"] = field(&Options::isotropic_noise_addition_probability);
    t["pointsource_noise_addition_probability"] = field(&Options::pointsource_noise_addition_probability);
    t["max_noises_per_minute"] = field(&Options::max_noises_per_minute);
    t["max_noises_per_recording"] = field(&Options::max_noises_per_recording);
    t["point_source_noise_rir"] = choice_field(&Options::point_source_noise_rir, point_source_noise_rir_choices());
    return t;
  }();
  return table;
}

}  // namespace

void set_augment_option(ReverberateDataOptions& options, const std::string& name, const py::handle& value) {
  auto it = fields().find(name);
  if (it == fields().end()) {
    std::string known;
    for (const auto& [n, f] : fields()) known += (known.empty() ? "" : ", ") + n;
    throw Error("Augmenter: unknown option '" + name + "' (reverberate-data's options here: " + known + ")");
  }
  try {
    it->second.set(options, value);
  } catch (const py::cast_error&) {
    throw Error("Augmenter: option '" + name + "' has a value of the wrong type");
  } catch (const Error& e) {
    throw Error("Augmenter: option '" + name + "': " + e.what());
  }
}

py::dict augment_options_dict(const ReverberateDataOptions& options) {
  py::dict d;
  for (const auto& [name, f] : fields()) d[py::str(name)] = f.get(options);
  return d;
}

}  // namespace tsrir::python
