// Kaldi RIR and noise lists (reverberate_data_dir.py's rir_list / noise_list, or scps) read by the
// library's own parser, for manifests (tsrir/manifests.py).
#include <pybind11/stl.h>

#include "bindings.h"
#include "io/data_dir.h"
#include "io/kaldi_lists.h"

namespace tsrir::python {
namespace {

namespace py = pybind11;

py::object optional_number(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::none(); }

}  // namespace

void bind_lists(py::module_& m) {
  m.def(
      "read_rir_list",
      [](const std::string& path) {
        std::vector<RirListEntry> entries;
        {
          py::gil_scoped_release release;
          entries = read_rir_list(path);
        }
        py::list out;
        for (const RirListEntry& e : entries) {
          py::dict d;
          d["rir_id"] = e.rir_id;
          d["room_id"] = e.room_id;
          d["receiver_position_id"] = e.receiver_position_id;
          d["source_position_id"] = e.source_position_id;
          d["rt60"] = optional_number(e.rt60);
          d["drr"] = optional_number(e.drr);
          d["cte"] = optional_number(e.cte);
          d["probability"] = optional_number(e.probability);
          d["rxfilename"] = e.rxfilename;
          out.append(d);
        }
        return out;
      },
      py::arg("path"), "A Kaldi rir_list (or <id> <rxfilename> scp), parsed as reverberate-data parses it.");
  m.def(
      "read_noise_list",
      [](const std::string& path) {
        std::vector<NoiseListEntry> entries;
        {
          py::gil_scoped_release release;
          entries = read_noise_list(path);
        }
        py::list out;
        for (const NoiseListEntry& e : entries) {
          py::dict d;
          d["noise_id"] = e.noise_id;
          d["noise_type"] = e.noise_type;
          d["bg_fg_type"] = choice_name(bg_fg_type_choices(), e.bg_fg_type);
          d["room_linkage"] = e.room_linkage;
          d["probability"] = optional_number(e.probability);
          d["rxfilename"] = e.rxfilename;
          out.append(d);
        }
        return out;
      },
      py::arg("path"), "A Kaldi noise_list (or scp), parsed as reverberate-data parses it.");
  m.def(
      "read_data_dir",
      [](const std::string& dir) {
        DataDir d;
        {
          py::gil_scoped_release release;
          d = read_data_dir(dir);
        }
        py::dict out;
        out["wav_scp"] = d.wav_scp;
        out["utt2spk"] = d.utt2spk;
        out["text"] = d.text;
        out["reco2dur"] = d.reco2dur;
        py::dict segments;
        for (const auto& [utt, seg] : d.segments)
          segments[py::str(utt)] = py::make_tuple(seg.recording_id, seg.start_s, seg.end_s);
        out["segments"] = segments;
        return out;
      },
      py::arg("dir"),
      "A Kaldi data dir, read and checked as the programs do: wav_scp, utt2spk, text, reco2dur,\n"
      "segments {utt: (recording, start_s, end_s)}.");
  m.def(
      "format_rir_list_line",
      [](const std::string& rir_id, const std::string& room_id, const std::string& rxfilename) {
        RirListEntry e;
        e.rir_id = rir_id;
        e.room_id = room_id;
        e.rxfilename = rxfilename;
        return format_rir_list_line(e);
      },
      py::arg("rir_id"), py::arg("room_id"), py::arg("rxfilename"), "One rir_list line (the writers' format).");
}

}  // namespace tsrir::python
