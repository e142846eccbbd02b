// Augmenter: reverberate-data's choices and its materialised reverberation (--write-wavs) for
// the recordings of one wav.scp, one utterance at a time, for on-the-fly augmentation in a data
// loader.
//
// The options become the plan as reverberate-data's do (to_plan(): the same checks, lists and
// planner options), and the choices are the library's plan_recordings() over the whole wav.scp,
// exactly as reverberate-data calls it (choices may depend on the other recordings: Kaldi's cyclic
// SNR lists walk the recordings in order), for copies 1..K, K growing when a later copy is asked
// for (plans of copies 1..K do not change when K grows: they come copy by copy). A (copy,
// recording) is then looked up, so the result depends on (options, wav.scp, seed, copy, id) only:
// not on which process asks or in which order. The samples are made by reverberate-data's
// PlanRenderer (augment/plan_renderer.h), as for a --write-wavs wav; tests/python checks the
// result against reverberate-data's wavs sample for sample.
//
// Thread/process safety: plans are mutex-protected and the renderer's load-once caches
// thread-safe; calls release the GIL. It pickles as its options and wav.scp (plans and caches are
// rebuilt), so it also travels to spawn-started DataLoader workers; forked workers inherit its caches.
#include <pybind11/stl.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>

#include "arrays.h"
#include "augment/augment_plan.h"
#include "augment/plan_renderer.h"
#include "augment/rate_policy.h"
#include "augment/reverberate_data.h"
#include "augmenter_options.h"
#include "bindings.h"
#include "io/audio_io.h"
#include "io/data_dir.h"
#include "util/error.h"

namespace tsrir::python {
namespace {

class Augmenter {
 public:
  Augmenter(ReverberateDataOptions options, std::map<std::string, std::string> wav_scp,
            std::map<std::string, double> durations)
      : options_(std::move(options)), wav_scp_(std::move(wav_scp)), durations_(std::move(durations)) {
    if (wav_scp_.empty()) throw Error("Augmenter: no recordings (give data_dir or recordings)");
    plan_ = to_plan(options_, OptionSpelling::kPython);
    // The data dir's rate (rate_policy.h): sample_rate, else the first recording's.
    const auto& [first_id, first_rx] = *wav_scp_.begin();
    dir_rate_ = std::make_unique<DirSampleRate>(plan_.sample_rate_hz, first_id, first_rx,
                                                "wav.scp: recording '" + first_id + "'");
    renderer_ = std::make_unique<PlanRenderer>(plan_.sources, plan_.reverb);
    // Each recording's duration, as reverberate-data takes it: given (reco2dur), else measured.
    for (const auto& [id, rx] : wav_scp_)
      if (!durations_.count(id)) durations_[id] = audio_duration_s(rx, "wav.scp: recording '" + id + "'");
  }

  const ReverberateDataOptions& options() const { return options_; }
  const std::map<std::string, std::string>& wav_scp() const { return wav_scp_; }
  const std::map<std::string, double>& durations() const { return durations_; }
  const AugmentSources& sources() const { return plan_.sources; }
  const DirSampleRate& dir_rate() const { return *dir_rate_; }

  // The plan of copy `copy` (>= 1) of recording `id`, noise offsets in seconds resolved.
  RecordingPlan plan(const std::string& id, int copy) {
    if (copy < 1) throw Error("copy must be >= 1 (reverberate-data numbers its copies from 1)");
    auto rec = wav_scp_.find(id);
    if (rec == wav_scp_.end()) throw Error("recording '" + id + "' is not in the Augmenter's wav.scp");
    std::lock_guard<std::mutex> lock(plan_mutex_);
    if (copy > planned_copies_) plan_copies(std::max(copy, 2 * planned_copies_));
    // Plans come copy by copy, recordings in wav.scp (map) order within a copy.
    const size_t index = static_cast<size_t>(copy - 1) * wav_scp_.size() +
                         static_cast<size_t>(std::distance(wav_scp_.begin(), rec));
    return plans_.at(index);
  }

  // The far-field copy, as reverberate-data --write-wavs makes it (before its 16-bit encoding): one
  // channel, or with multi_channel_output / split_channels one per channel of the plan's RIR (entry
  // .CH<c> of the split form is channel c - 1 of the multichannel one).
  std::vector<std::vector<float>> materialise(const std::vector<float>& speech, double fs, const RecordingPlan& plan) {
    if (options_.multi_channel_output || options_.split_channels) return renderer_->render_channels(speech, fs, plan);
    return {renderer_->render(speech, fs, plan)};
  }
  // (samples,); (channels, samples) with multi_channel_output (whatever the channel count); with
  // split_channels {id: (samples,)} keyed as reverberate-data --split-channels names the entries:
  // <new id>.CH<c> (c from 1) per channel of the RIR, the new id alone for a copy without one.
  py::object shaped(std::vector<std::vector<float>>&& channels, const RecordingPlan& plan) const {
    if (options_.multi_channel_output) return py::array(to_numpy(channels));
    if (!options_.split_channels) return py::array(to_numpy(std::move(channels.front())));
    py::dict entries;
    for (size_t c = 0; c < channels.size(); ++c) {
      const std::string id = plan.rir >= 0 ? plan.new_id + ".CH" + std::to_string(c + 1) : plan.new_id;
      entries[py::str(id)] = py::array(to_numpy(std::move(channels[c])));
    }
    return std::move(entries);
  }

 private:
  // reverberate-data's plans for copies 1..copies of the whole wav.scp (plan_mutex_ held).
  void plan_copies(int copies) {
    PlanOptions options = plan_.planning;
    options.num_replications = copies;
    std::map<long, double> noise_durations;
    std::vector<RecordingPlan> plans =
        plan_recordings(wav_scp_, durations_, plan_.sources, plan_.foreground_snrs, plan_.background_snrs, options);
    for (const RecordingPlan& p : plans)
      for (const PlannedNoise& n : p.noises)
        if (n.loop && !noise_durations.count(n.noise)) noise_durations[n.noise] = noise_duration(n.noise);
    resolve_noise_offsets(noise_durations, &plans);
    plans_ = std::move(plans);
    planned_copies_ = copies;
  }

  double noise_duration(long index) {
    auto it = noise_durations_.find(index);
    if (it != noise_durations_.end()) return it->second;
    const NoiseChoice& n = plan_.sources.noises[static_cast<size_t>(index)];
    return noise_durations_[index] = audio_duration_s(n.rxfilename, n.where + " (noise '" + n.id + "')");
  }

  ReverberateDataOptions options_;
  std::unique_ptr<DirSampleRate> dir_rate_;
  std::map<std::string, std::string> wav_scp_;
  std::map<std::string, double> durations_;
  ReverberatePlan plan_;
  std::unique_ptr<PlanRenderer> renderer_;  // reads plan_.sources
  std::mutex plan_mutex_;                   // plans_ and noise_durations_
  std::vector<RecordingPlan> plans_;
  int planned_copies_ = 0;
  std::map<long, double> noise_durations_;
};

py::object rir_id_or_none(const AugmentSources& sources, long rir) {
  if (rir < 0) return py::none();
  return py::str(sources.rirs[static_cast<size_t>(rir)].id);
}

py::dict plan_dict(const RecordingPlan& plan, const AugmentSources& sources) {
  py::dict d;
  d["id"] = plan.source_id;
  d["rxfilename"] = plan.source_rx;
  d["new_id"] = plan.new_id;
  d["copy"] = plan.copy;
  d["rir_id"] = rir_id_or_none(sources, plan.rir);
  d["room_id"] = plan.rir >= 0 ? py::object(py::str(sources.rirs[static_cast<size_t>(plan.rir)].room_id)) : py::none();
  d["rir_rxfilename"] =
      plan.rir >= 0 ? py::object(py::str(sources.rirs[static_cast<size_t>(plan.rir)].rxfilename)) : py::none();
  py::list noises;
  auto add = [&](long index, long rir, double snr_db, double start_s, double offset_s, bool loop) {
    const NoiseChoice& n = sources.noises[static_cast<size_t>(index)];
    py::dict e;
    e["noise_id"] = n.id;
    e["noise_type"] = n.noise_type;
    e["rxfilename"] = n.rxfilename;
    e["rir_id"] = rir_id_or_none(sources, rir);
    e["snr_db"] = snr_db;
    e["start_time_s"] = start_s;
    e["offset_s"] = offset_s;
    e["loop"] = loop;
    noises.append(e);
  };
  for (const PlannedNoise& n : plan.noises) add(n.noise, n.rir, n.snr_db, n.start_time_s, n.offset_s, n.loop);
  d["noises"] = noises;
  return d;
}

}  // namespace

void bind_augmenter(py::module_& m) {
  py::class_<Augmenter>(m, "Augmenter",
                        "reverberate-data's choices and reverberation for one utterance at a time.\n"
                        "data_dir: a Kaldi data dir (its wav.scp and reco2dur), or recordings: {id: rxfilename}\n"
                        "(durations: {id: seconds}, else measured): the recordings reverberate-data would be\n"
                        "given (its choices are made over all of them). Keyword options are reverberate-data's,\n"
                        "'_' for '-' (seed = --random-seed); Augmenter.option_defaults() lists them.\n"
                        "aug(speech, fs, id, copy=1) and aug.augment(id, copy=1) equal the wav that\n"
                        "reverberate-data --num-replications>=copy --write-wavs writes for copy `copy` of\n"
                        "recording `id` (before its 16-bit encoding).")
      .def(py::init([](const py::object& data_dir, const py::object& recordings, const py::object& durations,
                       const py::kwargs& kwargs) {
             ReverberateDataOptions options;
             for (const auto& [key, value] : kwargs) set_augment_option(options, key.cast<std::string>(), value);
             if (!data_dir.is_none() && !recordings.is_none()) throw Error("give data_dir or recordings, not both");
             std::map<std::string, std::string> wav_scp;
             std::map<std::string, double> lengths;
             if (!data_dir.is_none()) {
               DataDir dir = read_data_dir(data_dir.cast<std::string>());
               wav_scp = std::move(dir.wav_scp);
               lengths = std::move(dir.reco2dur);
             } else if (!recordings.is_none()) {
               wav_scp = recordings.cast<std::map<std::string, std::string>>();
             }
             if (!durations.is_none()) lengths = durations.cast<std::map<std::string, double>>();
             py::gil_scoped_release release;
             return std::make_unique<Augmenter>(std::move(options), std::move(wav_scp), std::move(lengths));
           }),
           py::arg("data_dir") = py::none(), py::arg("recordings") = py::none(), py::arg("durations") = py::none())
      .def_static(
          "option_defaults", [] { return augment_options_dict(ReverberateDataOptions{}); },
          "The options Augmenter takes, with reverberate-data's defaults.")
      .def_property_readonly("options", [](const Augmenter& a) { return augment_options_dict(a.options()); })
      .def(
          "plan",
          [](Augmenter& self, const std::string& id, int copy) {
            RecordingPlan p;
            {
              py::gil_scoped_release release;
              p = self.plan(id, copy);
            }
            return plan_dict(p, self.sources());
          },
          py::arg("id"), py::arg("copy") = 1,
          "What reverberate-data does to copy `copy` of recording `id`: RIR, noises with SNRs, offsets.")
      .def(
          "__call__",
          [](Augmenter& self, const py::handle& speech, double fs, const std::string& id, int copy) {
            std::vector<std::vector<float>> x = {to_samples(speech, "speech")};
            std::vector<std::vector<float>> y;
            RecordingPlan plan;
            {
              py::gil_scoped_release release;
              const std::vector<float> at_rate =
                  self.dir_rate().speech_at_rate(std::move(x), fs, "speech of recording '" + id + "'");
              plan = self.plan(id, copy);
              y = self.materialise(at_rate, self.dir_rate().rate_hz(), plan);
            }
            return self.shaped(std::move(y), plan);
          },
          py::arg("speech"), py::arg("fs"), py::arg("id"), py::arg("copy") = 1,
          "The far-field copy of one utterance given its samples (1-D float32) at fs Hz, at the data dir's\n"
          "rate (rate_policy.h: a speech at another rate is resampled when sample_rate was given, else refused).")
      .def(
          "augment",
          [](Augmenter& self, const std::string& id, int copy) {
            std::vector<std::vector<float>> y;
            double fs = 0;
            RecordingPlan plan;
            {
              py::gil_scoped_release release;
              plan = self.plan(id, copy);
              AudioInfo info;
              const std::string where = "wav.scp: recording '" + id + "'";
              std::vector<std::vector<float>> channels = read_audio_channels(plan.source_rx, &info, where);
              fs = self.dir_rate().rate_hz();
              y = self.materialise(self.dir_rate().speech_at_rate(std::move(channels), info.sample_rate_hz, where), fs,
                                   plan);
            }
            return py::make_tuple(self.shaped(std::move(y), plan), fs);
          },
          py::arg("id"), py::arg("copy") = 1,
          "Reads the recording's wav.scp entry (path or 'command |') and returns (far-field copy, fs): fs is\n"
          "the data dir's rate (a recording at another rate is resampled when sample_rate was given, else refused).")
      .def_property_readonly("sample_rate", [](const Augmenter& a) { return a.dir_rate().rate_hz(); },
                             "The data dir's rate in Hz (sample_rate, else the first recording's).")
      .def_property_readonly(
          "recordings",
          [](const Augmenter& a) {
            return std::vector<std::pair<std::string, std::string>>(a.wav_scp().begin(), a.wav_scp().end());
          },
          "[(id, rxfilename)] in wav.scp (byte) order, reverberate-data's order.")
      .def_property_readonly("num_rirs", [](const Augmenter& a) { return a.sources().rirs.size(); })
      .def_property_readonly("num_noises", [](const Augmenter& a) { return a.sources().noises.size(); })
      .def(py::pickle(
          [](const Augmenter& a) { return py::make_tuple(a.wav_scp(), a.durations(), augment_options_dict(a.options())); },
          [](const py::tuple& t) {
            if (t.size() != 3) throw Error("Augmenter: bad pickled state");
            ReverberateDataOptions options;
            for (const auto& [key, value] : t[2].cast<py::dict>())
              set_augment_option(options, key.cast<std::string>(), value);
            return std::make_unique<Augmenter>(std::move(options), t[0].cast<std::map<std::string, std::string>>(),
                                               t[1].cast<std::map<std::string, double>>());
          }));
}

}  // namespace tsrir::python
