// Augmenter: reverberate-data's choices and its materialised reverberation (--write-wavs) for
// the recordings of one wav.scp, one utterance at a time, for on-the-fly augmentation in a data
// loader.
//
// The choices are the library's plan_recordings() over the whole wav.scp, exactly as
// reverberate-data calls it (choices may depend on the other recordings: Kaldi's cyclic SNR
// lists walk the recordings in order), for copies 1..K, K growing when a later copy is asked for
// (plans of copies 1..K do not change when K grows: they come copy by copy). A (copy, recording)
// is then looked up, so the result depends on (options, wav.scp, seed, copy, id) only: not on
// which process asks or in which order. The samples are made as reverberate_data_dir() makes a
// --write-wavs wav: RIRs and noises read (and resampled) to the speech's rate by
// read_channels_at_rate(), then reverberate_channel(). plan_copies() and materialise() are the
// two places that follow reverberate_data.cc; tests/python checks the result against
// reverberate-data's wavs sample for sample.
//
// Thread/process safety: plans and the load-once caches of RIRs and noises are mutex-protected;
// calls release the GIL. It pickles as its options and wav.scp (plans and caches are rebuilt),
// so it also travels to spawn-started DataLoader workers; forked workers inherit its caches.
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <mutex>

#include "arrays.h"
#include "augment/augment_plan.h"
#include "augment/augment_sources.h"
#include "augment/rate_policy.h"
#include "augment/reverberate.h"
#include "augment/reverberate_data.h"
#include "augment/sampling.h"
#include "augment/wav_reverberate.h"
#include "augmenter_options.h"
#include "bindings.h"
#include "io/audio_io.h"
#include "io/data_dir.h"
#include "io/rxfile.h"
#include "util/error.h"
#include "util/strings.h"
#if TSRIR_PYTHON_NOISE_TYPES
#include "augment/noise_signal.h"
#endif

namespace tsrir::python {
namespace {

void check_probability(double p, const std::string& name) {
  if (p < 0 || p > 1) throw Error(name + " must be in [0, 1]");
}

class Augmenter {
 public:
  Augmenter(ReverberateDataOptions options, std::map<std::string, std::string> wav_scp,
            std::map<std::string, double> durations)
      : options_(std::move(options)), wav_scp_(std::move(wav_scp)), durations_(std::move(durations)) {
    if (wav_scp_.empty()) throw Error("Augmenter: no recordings (give data_dir or recordings)");
    // The data dir's rate (rate_policy.h): sample_rate, else the first recording's.
    const auto& [first_id, first_rx] = *wav_scp_.begin();
    dir_rate_ = std::make_unique<DirSampleRate>(options_.source_sampling_rate_hz, first_id, first_rx,
                                                "wav.scp: recording '" + first_id + "'");
    const ReverberateDataOptions& o = options_;
    check_probability(o.speech_rvb_probability, "speech_rvb_probability");
    if (o.noise_start != "random" && o.noise_start != "zero")
      throw Error("noise_start must be random or zero, got '" + o.noise_start + "'");
    sources_ = load_augment_sources(o.rir_set_parameters, o.noise_set_parameters, o.rir_smoothing_weight,
                                    o.noise_smoothing_weight);
    if (sources_.rirs.empty() && sources_.noises.empty())
      throw Error("nothing to apply: give rir_set_parameters and/or noise_set_parameters");
    plan_options_.prefix = o.prefix;
    plan_options_.speech_rvb_probability = o.speech_rvb_probability;
    plan_options_.random_seed = o.random_seed;
    reverb_ = o.reverb;
#if TSRIR_PYTHON_NOISE_TYPES
    check_probability(o.isotropic_noise_addition_probability, "isotropic_noise_addition_probability");
    check_probability(o.pointsource_noise_addition_probability, "pointsource_noise_addition_probability");
    if (o.max_noises_per_minute < 0) throw Error("max_noises_per_minute cannot be negative");
    if (o.max_noises_per_recording < 0) throw Error("max_noises_per_recording cannot be negative");
    if (o.point_source_noise_rir != "same-room" && o.point_source_noise_rir != "none")
      throw Error("point_source_noise_rir must be same-room or none, got '" + o.point_source_noise_rir + "'");
    foreground_snrs_ = std::make_unique<SnrSpec>(SnrSpec::parse(o.foreground_snrs, "foreground_snrs"));
    background_snrs_ = std::make_unique<SnrSpec>(SnrSpec::parse(o.background_snrs, "background_snrs"));
    plan_options_.noise.isotropic_noise_addition_probability = o.isotropic_noise_addition_probability;
    plan_options_.noise.pointsource_noise_addition_probability = o.pointsource_noise_addition_probability;
    plan_options_.noise.max_noises_per_minute = o.max_noises_per_minute;
    plan_options_.noise.max_noises_per_recording = o.max_noises_per_recording;
    plan_options_.noise.random_noise_start = o.noise_start == "random";
    plan_options_.noise.point_source_noise_rir = o.point_source_noise_rir == "same-room";
    // Each recording's duration, as reverberate-data takes it: given (reco2dur), else measured.
    for (const auto& [id, rx] : wav_scp_)
      if (!durations_.count(id)) durations_[id] = audio_duration_s(rx, "wav.scp: recording '" + id + "'");
#else
    check_probability(o.noise_addition_probability, "noise_addition_probability");
    snrs_ = std::make_unique<SnrSpec>(SnrSpec::parse(o.snrs, "snrs"));
    plan_options_.noise_addition_probability = o.noise_addition_probability;
    plan_options_.random_noise_start = o.noise_start == "random";
    reverb_.loop_additive_signals = true;
#endif
  }

  const ReverberateDataOptions& options() const { return options_; }
  const std::map<std::string, std::string>& wav_scp() const { return wav_scp_; }
  const std::map<std::string, double>& durations() const { return durations_; }
  const AugmentSources& sources() const { return sources_; }
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

  // The far-field copy, as reverberate-data --write-wavs makes it (before its 16-bit encoding).
  std::vector<float> materialise(const std::vector<float>& speech, double fs, const RecordingPlan& plan) {
    std::shared_ptr<const PreparedRir> rir;
    if (plan.rir >= 0) rir = prepared_rir(plan.rir, fs);
    std::vector<AdditiveSignal> additive;
#if TSRIR_PYTHON_NOISE_TYPES
    for (const PlannedNoise& planned : plan.noises) {
      std::shared_ptr<const PreparedRir> noise_rir;
      if (planned.rir >= 0) noise_rir = prepared_rir(planned.rir, fs);
      additive.push_back(planned_noise_signal(planned, noise(planned.noise, fs), noise_rir.get(), fs));
    }
#else
    if (plan.noise >= 0) {
      AdditiveSignal a;
      a.samples = noise(plan.noise, fs);
      a.snr_db = plan.snr_db;
      a.start_time_s = 0.0;
      a.offset_s = plan.noise_offset_s;
      additive.push_back(std::move(a));
    }
#endif
    return reverberate_channel(speech, fs, rir.get(), additive, reverb_);
  }

 private:
  // reverberate-data's plans for copies 1..copies of the whole wav.scp (plan_mutex_ held).
  void plan_copies(int copies) {
    PlanOptions options = plan_options_;
    options.num_replications = copies;
    std::map<long, double> noise_durations;
#if TSRIR_PYTHON_NOISE_TYPES
    std::vector<RecordingPlan> plans =
        plan_recordings(wav_scp_, durations_, sources_, *foreground_snrs_, *background_snrs_, options);
    for (const RecordingPlan& p : plans)
      for (const PlannedNoise& n : p.noises)
        if (n.loop && !noise_durations.count(n.noise)) noise_durations[n.noise] = noise_duration(n.noise);
#else
    std::vector<RecordingPlan> plans = plan_recordings(wav_scp_, sources_, *snrs_, options);
    for (const RecordingPlan& p : plans)
      if (p.noise >= 0 && !noise_durations.count(p.noise)) noise_durations[p.noise] = noise_duration(p.noise);
#endif
    resolve_noise_offsets(noise_durations, &plans);
    plans_ = std::move(plans);
    planned_copies_ = copies;
  }

  std::shared_ptr<const PreparedRir> prepared_rir(long index, double fs) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = rirs_.find({index, fs});
      if (it != rirs_.end()) return it->second;
    }
    const RirChoice& choice = sources_.rirs[static_cast<size_t>(index)];
    const std::string what = choice.where + " (RIR '" + choice.id + "')";
    auto prepared =
        std::make_shared<const PreparedRir>(first_channel_of(read_channels_at_rate(choice.rxfilename, fs, what), what), fs);
    std::lock_guard<std::mutex> lock(mutex_);
    return rirs_.emplace(std::make_pair(index, fs), prepared).first->second;
  }

  std::shared_ptr<const std::vector<float>> noise(long index, double fs) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = noises_.find({index, fs});
      if (it != noises_.end()) return it->second;
    }
    const NoiseChoice& choice = sources_.noises[static_cast<size_t>(index)];
    const std::string what = choice.where + " (noise '" + choice.id + "')";
    auto samples =
        std::make_shared<const std::vector<float>>(first_channel_of(read_channels_at_rate(choice.rxfilename, fs, what), what));
    std::lock_guard<std::mutex> lock(mutex_);
    return noises_.emplace(std::make_pair(index, fs), samples).first->second;
  }

  double noise_duration(long index) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = noise_durations_.find(index);
      if (it != noise_durations_.end()) return it->second;
    }
    const NoiseChoice& n = sources_.noises[static_cast<size_t>(index)];
    const double d = audio_duration_s(n.rxfilename, n.where + " (noise '" + n.id + "')");
    std::lock_guard<std::mutex> lock(mutex_);
    return noise_durations_.emplace(index, d).first->second;
  }

  ReverberateDataOptions options_;
  std::unique_ptr<DirSampleRate> dir_rate_;
  std::map<std::string, std::string> wav_scp_;
  std::map<std::string, double> durations_;
  AugmentSources sources_;
#if TSRIR_PYTHON_NOISE_TYPES
  std::unique_ptr<SnrSpec> foreground_snrs_, background_snrs_;
#else
  std::unique_ptr<SnrSpec> snrs_;
#endif
  PlanOptions plan_options_;
  ReverbOptions reverb_;
  std::mutex mutex_;        // the caches
  std::mutex plan_mutex_;   // plans_
  std::vector<RecordingPlan> plans_;
  int planned_copies_ = 0;
  std::map<std::pair<long, double>, std::shared_ptr<const PreparedRir>> rirs_;
  std::map<std::pair<long, double>, std::shared_ptr<const std::vector<float>>> noises_;
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
#if TSRIR_PYTHON_NOISE_TYPES
  for (const PlannedNoise& n : plan.noises) add(n.noise, n.rir, n.snr_db, n.start_time_s, n.offset_s, n.loop);
#else
  if (plan.noise >= 0) add(plan.noise, -1, plan.snr_db, 0.0, plan.noise_offset_s, true);
#endif
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
            std::vector<float> y;
            {
              py::gil_scoped_release release;
              const std::vector<float> at_rate =
                  self.dir_rate().speech_at_rate(std::move(x), fs, "speech of recording '" + id + "'");
              y = self.materialise(at_rate, self.dir_rate().rate_hz(), self.plan(id, copy));
            }
            return to_numpy(std::move(y));
          },
          py::arg("speech"), py::arg("fs"), py::arg("id"), py::arg("copy") = 1,
          "The far-field copy of one utterance given its samples (1-D float32) at fs Hz, at the data dir's\n"
          "rate (rate_policy.h: a speech at another rate is resampled when sample_rate was given, else refused).")
      .def(
          "augment",
          [](Augmenter& self, const std::string& id, int copy) {
            std::vector<float> y;
            double fs = 0;
            {
              py::gil_scoped_release release;
              const RecordingPlan plan = self.plan(id, copy);
              AudioInfo info;
              const std::string where = "wav.scp: recording '" + id + "'";
              std::vector<std::vector<float>> channels = read_audio_channels(plan.source_rx, &info, where);
              fs = self.dir_rate().rate_hz();
              y = self.materialise(self.dir_rate().speech_at_rate(std::move(channels), info.sample_rate_hz, where), fs,
                                   plan);
            }
            return py::make_tuple(to_numpy(std::move(y)), fs);
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
