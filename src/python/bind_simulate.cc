// simulate(): one RIR from rir-simulate's model. The arguments become one room-list line that
// the room-list parser reads (so t60/absorption/scattering and every other key mean exactly what
// they mean in a room list), then the same Model::parse / prepare_room / render calls as
// simulate_room_list(): for the same line, --fs, --length, --model and --seed the samples are
// those rir-simulate --format=float writes.
#include <pybind11/stl.h>

#include <cinttypes>
#include <cstdio>

#include "arrays.h"
#include "bindings.h"
#include "sim/model.h"
#include "sim/room_list.h"
#include "sim/simulate.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir::python {
namespace {

// Exact text of a double (17 significant digits read back to the same value).
std::string exact(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// A number or a sequence of numbers as a room-list value "a,b,c".
std::string values_text(const py::handle& value, const std::string& key) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return exact(value.cast<double>());
  std::string out;
  try {
    for (const py::handle& v : value) out += (out.empty() ? "" : ",") + exact(v.cast<double>());
  } catch (const py::error_already_set&) {
    throw Error(key + ": expected a number or a sequence of numbers");
  } catch (const py::cast_error&) {
    throw Error(key + ": expected a number or a sequence of numbers");
  }
  return out;
}

// mic= of a room-list line: one position (x, y, z), or an array's positions ((x, y, z), ...) as
// "x,y,z;x,y,z;...".
std::string mics_text(const py::handle& mic) {
  if (py::isinstance<py::str>(mic) || !py::isinstance<py::sequence>(mic)) return values_text(mic, "mic");
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(mic);
  if (seq.size() == 0 || !py::isinstance<py::sequence>(seq[0])) return values_text(mic, "mic");
  std::string out;
  for (const py::handle& one : seq) out += (out.empty() ? "" : ";") + values_text(one, "mic");
  return out;
}

}  // namespace

void bind_simulate(py::module_& m) {
  m.def(
      "room_list_line",
      [](const py::handle& room, const py::handle& src, const py::handle& mic, const py::object& t60,
         const py::object& absorption, const py::object& scattering, const std::string& rir_id, const py::dict& extra) {
        std::string line = rir_id + " room=" + values_text(room, "room") + " src=" + values_text(src, "src") +
                           " mic=" + mics_text(mic);
        if (!t60.is_none()) line += " t60=" + values_text(t60, "t60");
        if (!absorption.is_none()) line += " absorption=" + values_text(absorption, "absorption");
        if (!scattering.is_none()) line += " scattering=" + values_text(scattering, "scattering");
        for (const auto& [key, value] : extra) line += " " + key.cast<std::string>() + "=" + values_text(value, "extra");
        return line;
      },
      py::arg("room"), py::arg("src"), py::arg("mic"), py::arg("t60") = py::none(),
      py::arg("absorption") = py::none(), py::arg("scattering") = py::none(), py::arg("rir_id") = "rir",
      py::arg("extra") = py::dict(),
      "The rir-simulate room-list line that simulate() renders for these arguments.");
  m.def(
      "simulate_line",
      [](const std::string& line, double fs, const std::string& model_spec, int64_t seed, const std::string& length) {
        std::vector<std::vector<float>> channels;
        {
          py::gil_scoped_release release;
          if (!(fs >= 1000.0 && fs <= 384000.0))
            throw Error("fs must be in [1000, 384000] Hz, got " + format_double(fs));
          const sim::RoomSpec room = sim::parse_room_list_line(line, "simulate()");
          const sim::Model model = sim::Model::parse(model_spec);
          const sim::RoomSpec prepared = model.prepare_room(room);
          const size_t n = sim::rir_length_samples(length, model.auto_length_s(prepared), fs);
          if (n < 16) throw Error("simulate(): RIR length below 16 samples");
          for (Signal& c : model.render_array(room, fs, n, static_cast<uint64_t>(seed))) {
            channels.push_back(std::move(c.samples));
          }
        }
        // One microphone: (samples,) as before; an array: (microphones, samples).
        if (channels.size() == 1) return py::array(to_numpy(std::move(channels.front())));
        return py::array(to_numpy(channels));
      },
      py::arg("line"), py::arg("fs") = 16000.0, py::arg("model") = "gas", py::arg("seed") = 0,
      py::arg("length") = "1.0",
      "Renders one rir-simulate room-list line ('<rir-id> room=.. src=.. mic=.. [key=value ...]'): "
      "(samples,) for one microphone, (microphones, samples) for an array.");
  m.def(
      "read_room_list",
      [](const std::string& path) {
        std::vector<sim::RoomSpec> rooms;
        {
          py::gil_scoped_release release;
          rooms = sim::read_room_list(path);
        }
        py::list out;
        for (const sim::RoomSpec& r : rooms) {
          py::dict d;
          d["rir_id"] = r.rir_id;
          d["room_id"] = r.effective_room_id();
          d["room_m"] = r.size_m;
          d["src_m"] = r.source_m;
          d["mic_m"] = r.mic_m;
          py::list mics;
          for (size_t m = 0; m < r.num_mics(); ++m) mics.append(py::cast(r.mic_position_m(m)));
          d["mics_m"] = mics;
          d["line"] = sim::format_room_list_line(r);
          out.append(d);
        }
        return out;
      },
      py::arg("path"), "An rir-simulate room list, parsed by the simulator's own parser: one dict per RIR.");
  m.def("model_components_help", &sim::model_components_help, "The simulator's components (rir-simulate --help).");
  m.def("room_list_keys_help", &sim::room_list_keys_help, "The room-list keys (rir-simulate --help).");
}

}  // namespace tsrir::python
