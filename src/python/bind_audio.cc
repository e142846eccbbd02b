// Audio in and out through the toolkit's own reader (libsndfile, rxfilenames with pipes) and WAV
// writer, so a Python pipeline reads and writes samples exactly as the programs do.
#include <utility>

#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "io/audio_io.h"

namespace tsrir::python {

void bind_audio(py::module_& m) {
  m.def(
      "read_audio",
      [](const std::string& rx) {
        AudioInfo info;
        std::vector<std::vector<float>> channels;
        {
          py::gil_scoped_release release;
          channels = read_audio_channels(rx, &info);
        }
        return py::make_tuple(to_numpy(channels), info.sample_rate_hz);
      },
      py::arg("rxfilename"),
      "Reads an audio file, '-' or 'command |' (Kaldi rxfilename) as the programs do.\n"
      "Returns (samples, fs): samples is float32 (channels, n), full scale 1.0 (int16 / 32768).");
  m.def(
      "audio_info",
      [](const std::string& path) {
        AudioInfo info;
        {
          py::gil_scoped_release release;
          info = probe_audio(path);
        }
        py::dict d;
        d["sample_rate"] = info.sample_rate_hz;
        d["channels"] = info.channels;
        d["frames"] = info.frames;
        d["format"] = info.format;
        return d;
      },
      py::arg("path"), "The header of an audio file (libsndfile): sample_rate, channels, frames, format.");
  m.def(
      "encode_wav",
      [](const py::handle& samples, double fs, const std::string& format) {
        std::vector<std::vector<float>> channels = to_channels(samples, "samples");
        const SampleFormat f = parse_sample_format(format);
        std::vector<char> bytes;
        {
          py::gil_scoped_release release;
          AudioWriteOptions o;
          o.format = f;
          bytes = encode_wav(channels, fs, o);
        }
        return py::bytes(bytes.data(), bytes.size());
      },
      py::arg("samples"), py::arg("fs"), py::arg("format") = "int16",
      "The WAV file the programs would write for these samples (1-D or (channels, n)), as bytes.\n"
      "format: 'int16' (rounded to nearest and clipped, as every program writes) or 'float'.");
  m.def(
      "write_wav",
      [](const std::string& path, const py::handle& samples, double fs, const std::string& format) {
        std::vector<std::vector<float>> channels = to_channels(samples, "samples");
        const SampleFormat f = parse_sample_format(format);
        py::gil_scoped_release release;
        AudioWriteOptions o;
        o.format = f;
        write_wav_channels(path, channels, fs, o);
      },
      py::arg("path"), py::arg("samples"), py::arg("fs"), py::arg("format") = "int16",
      "Writes a WAV file atomically (temporary name, then rename), as the programs do.");
  m.def(
      "resample",
      [](const py::handle& samples, double from_hz, double to_hz) {
        std::vector<float> x = to_samples(samples, "samples");
        std::vector<float> y;
        {
          py::gil_scoped_release release;
          y = resample(x, from_hz, to_hz);
        }
        return to_numpy(std::move(y));
      },
      py::arg("samples"), py::arg("from_hz"), py::arg("to_hz"),
      "libsox 'rate -v' resampling, the one every program uses.");
}

}  // namespace tsrir::python
