// reverberate(): wav-reverberate's in-memory body, wav_reverberate_channels(), with the same
// configuration struct the program fills from its options. Given the samples the program reads
// (tsrir.read_audio), the result equals the program's output before its 16-bit encoding, and
// tsrir.encode_wav() of it equals the program's output file byte for byte (tests/python).
#include <pybind11/stl.h>

#include "arrays.h"
#include "augment/wav_reverberate.h"
#include "bindings.h"
#include "io/audio_io.h"
#include "util/error.h"

namespace tsrir::python {
namespace {

// Additive signals: None, one array, or a list of arrays (each 1-D or (channels, n)).
std::vector<std::vector<std::vector<float>>> additive_list(const py::object& noise) {
  std::vector<std::vector<std::vector<float>>> out;
  if (noise.is_none()) return out;
  if (py::isinstance<py::list>(noise) || py::isinstance<py::tuple>(noise)) {
    size_t i = 0;
    for (const py::handle& n : noise) out.push_back(to_channels(n, "noise[" + std::to_string(i++) + "]"));
  } else {
    out.push_back(to_channels(noise, "noise"));
  }
  return out;
}

// None, one number (used for every additive signal) or one per signal.
std::vector<double> per_signal(const py::object& values, size_t count, double absent, const std::string& what) {
  if (values.is_none()) return std::vector<double>(count, absent);
  if (py::isinstance<py::float_>(values) || py::isinstance<py::int_>(values))
    return std::vector<double>(count, values.cast<double>());
  std::vector<double> out = values.cast<std::vector<double>>();
  if (out.size() != count)
    throw Error(what + " has " + std::to_string(out.size()) + " values for " + std::to_string(count) +
                " additive signal(s)");
  return out;
}

}  // namespace

void bind_reverberate(py::module_& m) {
  m.def(
      "reverberate_channels",
      [](const py::handle& speech, const py::object& rir, double fs, const py::object& noise, const py::object& snr_db,
         const py::object& start_time_s, const py::object& offset_s, bool shift_output, bool normalize_output,
         float volume, float duration_s, const std::string& snr_reference, bool loop_noise, bool multi_channel_output,
         int input_channel, int rir_channel, int noise_channel, double rir_fs, double noise_fs) {
        WavReverberateOptions config;
        config.multi_channel_output = multi_channel_output;
        config.input_wave_channel = input_channel;
        config.rir_channel = rir_channel;
        config.noise_channel = noise_channel;
        config.reverb.shift_output = shift_output;
        config.reverb.normalize_output = normalize_output;
        // float, as the program reads --volume and --duration (Kaldi's BaseFloat).
        config.reverb.volume = volume;
        config.reverb.duration_s = duration_s;
        config.reverb.snr_reference = parse_snr_reference(snr_reference);
        config.reverb.loop_additive_signals = loop_noise;

        const std::vector<std::vector<float>> input = to_channels(speech, "speech");
        std::vector<std::vector<float>> rir_channels;
        if (!rir.is_none()) rir_channels = to_channels(rir, "rir");
        std::vector<std::vector<std::vector<float>>> additive = additive_list(noise);
        if (!additive.empty() && snr_db.is_none()) throw Error("noise given without snr_db");
        const std::vector<double> snrs = per_signal(snr_db, additive.size(), 0.0, "snr_db");
        const std::vector<double> starts = per_signal(start_time_s, additive.size(), 0.0, "start_time_s");
        const std::vector<double> offsets = per_signal(offset_s, additive.size(), 0.0, "offset_s");
        std::vector<std::vector<float>> out;
        {
          py::gil_scoped_release release;
          // The program resamples RIRs and additive signals read at another rate to the speech's.
          if (rir_fs > 0 && rir_fs != fs)
            for (auto& c : rir_channels) c = resample(c, rir_fs, fs);
          if (noise_fs > 0 && noise_fs != fs)
            for (auto& signal : additive)
              for (auto& c : signal) c = resample(c, noise_fs, fs);
          out = wav_reverberate_channels(input, fs, rir_channels, additive, snrs, starts, offsets, config);
        }
        return to_numpy(out);
      },
      py::arg("speech"), py::arg("rir"), py::arg("fs"), py::arg("noise") = py::none(), py::arg("snr_db") = py::none(),
      py::arg("start_time_s") = py::none(), py::arg("offset_s") = py::none(), py::arg("shift_output") = true,
      py::arg("normalize_output") = true, py::arg("volume") = 0.0f, py::arg("duration_s") = 0.0f,
      py::arg("snr_reference") = "early", py::arg("loop_noise") = false, py::arg("multi_channel_output") = false,
      py::arg("input_channel") = 0, py::arg("rir_channel") = 0, py::arg("noise_channel") = 0,
      py::arg("rir_fs") = 0.0, py::arg("noise_fs") = 0.0,
      "wav-reverberate in memory: returns (output channels, samples) float32.");
  m.def(
      "rir_shift_index",
      [](const py::handle& rir, double fs) {
        PreparedRir prepared(to_samples(rir, "rir"), fs);
        return prepared.peak_index();
      },
      py::arg("rir"), py::arg("fs"),
      "The sample wav-reverberate --shift-output=true advances the output by: the RIR's signed maximum\n"
      "(Kaldi's direct-path estimate).");
}

}  // namespace tsrir::python
