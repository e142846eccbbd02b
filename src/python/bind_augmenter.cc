// Augmenter: reverberate-data's choices and its materialised reverberation (--write-wavs) for
// the recordings of one wav.scp, one utterance at a time, for on-the-fly augmentation in a data
// loader.
//
// The choices are the library's plan_recordings() over the whole wav.scp, exactly as
// reverberate-data calls it (its choices may depend on the other recordings: Kaldi's cyclic SNR
// lists walk the recordings in order), for copies 1..K, K growing when a later copy is asked for
// (plans of copies 1..K do not change when K grows). A (copy, recording) is then looked up, so the
// result depends on (settings, wav.scp, seed, copy, id) only: not on which process or in which
// order a data loader asks. The samples are made as reverberate_data_dir() makes a --write-wavs
// wav: channel 0 of the RIR and noise, read (and resampled) to the speech's rate by
// read_channels_at_rate(), then reverberate_channel(). tests/python checks the result against
// reverberate-data's wavs sample for sample; materialise() and plan_copies() below are the two
// places that follow reverberate_data.cc.
//
// Thread/process safety: plans and load-once caches of RIRs and noises are mutex-protected;
// calls release the GIL. It pickles as its settings and wav.scp (plans and caches are rebuilt),
// so it also travels to spawn-started DataLoader workers; forked workers inherit its caches.
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <mutex>

#include "arrays.h"
#include "augment/augment_plan.h"
#include "augment/augment_sources.h"
#include "augment/reverberate.h"
#include "augment/reverberate_data.h"
#include "augment/sampling.h"
#include "augment/wav_reverberate.h"
#include "bindings.h"
#include "io/audio_io.h"
#include "io/data_dir.h"
#include "io/rxfile.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir::python {
namespace {

// Settings are reverberate-data's own option struct (ReverberateDataOptions), defaults included;
// only the fields that decide what happens to one recording are used (not num_replications,
// include_original_data, write_wavs, threads, ...).
using AugmenterSettings = ReverberateDataOptions;

class Augmenter {
 public:
  Augmenter(AugmenterSettings settings, std::map<std::string, std::string> wav_scp)
      : settings_(std::move(settings)), wav_scp_(std::move(wav_scp)) {
    if (wav_scp_.empty()) throw Error("Augmenter: no recordings (give data_dir or recordings)");
    const AugmenterSettings& s = settings_;
    if (s.speech_rvb_probability < 0 || s.speech_rvb_probability > 1)
      throw Error("speech_rvb_probability must be in [0, 1]");
    if (s.noise_addition_probability < 0 || s.noise_addition_probability > 1)
      throw Error("noise_addition_probability must be in [0, 1]");
    if (s.noise_start != "random" && s.noise_start != "zero")
      throw Error("noise_start must be random or zero, got '" + s.noise_start + "'");
    sources_ = load_augment_sources(s.rir_set_parameters, s.noise_set_parameters, s.rir_smoothing_weight,
                                    s.noise_smoothing_weight);
    if (sources_.rirs.empty() && sources_.noises.empty())
      throw Error("nothing to apply: give rir_set_parameters and/or noise_set_parameters");
    snrs_ = std::make_unique<SnrSpec>(SnrSpec::parse(s.snrs, "snrs"));
    plan_options_.prefix = s.prefix;
    plan_options_.speech_rvb_probability = s.speech_rvb_probability;
    plan_options_.noise_addition_probability = s.noise_addition_probability;
    plan_options_.random_noise_start = s.noise_start == "random";
    plan_options_.random_seed = s.random_seed;
    reverb_.shift_output = s.shift_output;
    reverb_.normalize_output = s.normalize_output;
    reverb_.snr_reference = s.snr_reference;
    reverb_.loop_additive_signals = true;
  }

  const AugmenterSettings& settings() const { return settings_; }
  const std::map<std::string, std::string>& wav_scp() const { return wav_scp_; }
  const AugmentSources& sources() const { return sources_; }

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

  std::vector<float> materialise(const std::vector<float>& speech, double fs, const RecordingPlan& plan) {
    std::shared_ptr<const PreparedRir> rir;
    if (plan.rir >= 0) rir = prepared_rir(plan.rir, fs);
    std::vector<AdditiveSignal> additive;
    if (plan.noise >= 0) {
      AdditiveSignal a;
      a.samples = noise(plan.noise, fs);
      a.snr_db = plan.snr_db;
      a.start_time_s = 0.0;
      a.offset_s = plan.noise_offset_s;
      additive.push_back(std::move(a));
    }
    // As reverberate-data's --write-wavs: every recording goes through reverberate_channel().
    return reverberate_channel(speech, fs, rir.get(), additive, reverb_);
  }

 private:
  // reverberate-data's plan for copies 1..copies of the whole wav.scp (plan_mutex_ held).
  void plan_copies(int copies) {
    PlanOptions options = plan_options_;
    options.num_replications = copies;
    std::vector<RecordingPlan> plans = plan_recordings(wav_scp_, sources_, *snrs_, options);
    std::map<long, double> durations;
    for (const RecordingPlan& p : plans)
      if (p.noise >= 0 && !durations.count(p.noise)) durations[p.noise] = noise_duration(p.noise);
    resolve_noise_offsets(durations, &plans);
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
    std::vector<std::vector<float>> ch =
        read_channels_at_rate(choice.rxfilename, fs, choice.where + " (RIR '" + choice.id + "')");
    auto prepared = std::make_shared<const PreparedRir>(std::move(ch.at(0)), fs);
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
    std::vector<std::vector<float>> ch =
        read_channels_at_rate(choice.rxfilename, fs, choice.where + " (noise '" + choice.id + "')");
    auto samples = std::make_shared<const std::vector<float>>(std::move(ch.at(0)));
    std::lock_guard<std::mutex> lock(mutex_);
    return noises_.emplace(std::make_pair(index, fs), samples).first->second;
  }

  double noise_duration(long index) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = durations_.find(index);
      if (it != durations_.end()) return it->second;
    }
    const NoiseChoice& n = sources_.noises[static_cast<size_t>(index)];
    const double d = audio_duration_s(n.rxfilename, n.where + " (noise '" + n.id + "')");
    std::lock_guard<std::mutex> lock(mutex_);
    return durations_.emplace(index, d).first->second;
  }

  AugmenterSettings settings_;
  std::map<std::string, std::string> wav_scp_;
  AugmentSources sources_;
  std::unique_ptr<SnrSpec> snrs_;
  PlanOptions plan_options_;
  ReverbOptions reverb_;
  std::mutex mutex_;        // the caches
  std::mutex plan_mutex_;   // plans_
  std::vector<RecordingPlan> plans_;
  int planned_copies_ = 0;
  std::map<std::pair<long, double>, std::shared_ptr<const PreparedRir>> rirs_;
  std::map<std::pair<long, double>, std::shared_ptr<const std::vector<float>>> noises_;
  std::map<long, double> durations_;
};

py::dict plan_dict(const RecordingPlan& plan, const AugmentSources& sources) {
  py::dict d;
  d["id"] = plan.source_id;
  d["rxfilename"] = plan.source_rx;
  d["new_id"] = plan.new_id;
  d["copy"] = plan.copy;
  py::object none = py::none();
  if (plan.rir >= 0) {
    const RirChoice& r = sources.rirs[static_cast<size_t>(plan.rir)];
    d["rir_id"] = r.id;
    d["room_id"] = r.room_id;
    d["rir_rxfilename"] = r.rxfilename;
  } else {
    d["rir_id"] = none;
    d["room_id"] = none;
    d["rir_rxfilename"] = none;
  }
  if (plan.noise >= 0) {
    const NoiseChoice& n = sources.noises[static_cast<size_t>(plan.noise)];
    d["noise_id"] = n.id;
    d["noise_type"] = n.noise_type;
    d["noise_rxfilename"] = n.rxfilename;
    d["snr_db"] = plan.snr_db;
    d["noise_offset_s"] = plan.noise_offset_s;
  } else {
    d["noise_id"] = none;
    d["noise_type"] = none;
    d["noise_rxfilename"] = none;
    d["snr_db"] = none;
    d["noise_offset_s"] = none;
  }
  return d;
}

py::tuple settings_tuple(const AugmenterSettings& s, const std::map<std::string, std::string>& wav_scp) {
  return py::make_tuple(wav_scp, s.rir_set_parameters, s.noise_set_parameters, s.snrs, s.speech_rvb_probability,
                        s.noise_addition_probability, s.noise_start, s.shift_output, s.normalize_output,
                        snr_reference_name(s.snr_reference), s.rir_smoothing_weight, s.noise_smoothing_weight,
                        s.random_seed, s.prefix);
}

std::unique_ptr<Augmenter> augmenter_from_tuple(const py::tuple& state) {
  if (state.size() != 14) throw Error("Augmenter: bad pickled state");
  auto wav_scp = state[0].cast<std::map<std::string, std::string>>();
  const py::tuple t = state[py::slice(1, 14, 1)];
  AugmenterSettings s;
  s.rir_set_parameters = t[0].cast<std::vector<std::string>>();
  s.noise_set_parameters = t[1].cast<std::vector<std::string>>();
  s.snrs = t[2].cast<std::string>();
  s.speech_rvb_probability = t[3].cast<double>();
  s.noise_addition_probability = t[4].cast<double>();
  s.noise_start = t[5].cast<std::string>();
  s.shift_output = t[6].cast<bool>();
  s.normalize_output = t[7].cast<bool>();
  s.snr_reference = parse_snr_reference(t[8].cast<std::string>());
  s.rir_smoothing_weight = t[9].cast<double>();
  s.noise_smoothing_weight = t[10].cast<double>();
  s.random_seed = t[11].cast<uint64_t>();
  s.prefix = t[12].cast<std::string>();
  return std::make_unique<Augmenter>(std::move(s), std::move(wav_scp));
}

}  // namespace

void bind_augmenter(py::module_& m) {
  const AugmenterSettings d;
  py::class_<Augmenter>(m, "Augmenter",
                        "reverberate-data's choices and reverberation for one utterance at a time.\n"
                        "data_dir: a Kaldi data dir (its wav.scp), or recordings: {id: rxfilename}: the\n"
                        "recordings reverberate-data would be given (its choices are made over all of them).\n"
                        "Other arguments are reverberate-data's options: rir_set_parameters / noise_set_parameters\n"
                        "are lists of '[weight,] list-file' (--rir-set-parameters, --noise-set-parameters),\n"
                        "snrs its --snrs ('lo:hi', 'a,b,c' or 'x'), seed its --random-seed.\n"
                        "aug(speech, fs, id, copy=1) and aug.augment(id, copy=1) equal the wav that\n"
                        "reverberate-data --num-replications>=copy --write-wavs writes for copy `copy` of\n"
                        "recording `id` (before its 16-bit encoding).")
      .def(py::init([](const py::object& data_dir, const py::object& recordings, std::vector<std::string> rir_sets, std::vector<std::string> noise_sets, std::string snrs,
                       double speech_rvb_probability, double noise_addition_probability, std::string noise_start,
                       bool shift_output, bool normalize_output, std::string snr_reference,
                       double rir_smoothing_weight, double noise_smoothing_weight, uint64_t seed, std::string prefix) {
             AugmenterSettings s;
             s.rir_set_parameters = std::move(rir_sets);
             s.noise_set_parameters = std::move(noise_sets);
             s.snrs = std::move(snrs);
             s.speech_rvb_probability = speech_rvb_probability;
             s.noise_addition_probability = noise_addition_probability;
             s.noise_start = std::move(noise_start);
             s.shift_output = shift_output;
             s.normalize_output = normalize_output;
             s.snr_reference = parse_snr_reference(snr_reference);
             s.rir_smoothing_weight = rir_smoothing_weight;
             s.noise_smoothing_weight = noise_smoothing_weight;
             s.random_seed = seed;
             s.prefix = std::move(prefix);
             std::map<std::string, std::string> wav_scp;
             if (!data_dir.is_none() && !recordings.is_none()) throw Error("give data_dir or recordings, not both");
             if (!data_dir.is_none()) {
               wav_scp = read_data_dir(data_dir.cast<std::string>()).wav_scp;
             } else if (!recordings.is_none()) {
               wav_scp = recordings.cast<std::map<std::string, std::string>>();
             }
             py::gil_scoped_release release;
             return std::make_unique<Augmenter>(std::move(s), std::move(wav_scp));
           }),
           py::arg("data_dir") = py::none(), py::arg("recordings") = py::none(), py::arg("rir_set_parameters") = std::vector<std::string>{},
           py::arg("noise_set_parameters") = std::vector<std::string>{}, py::arg("snrs") = d.snrs,
           py::arg("speech_rvb_probability") = d.speech_rvb_probability,
           py::arg("noise_addition_probability") = d.noise_addition_probability, py::arg("noise_start") = d.noise_start,
           py::arg("shift_output") = d.shift_output, py::arg("normalize_output") = d.normalize_output,
           py::arg("snr_reference") = snr_reference_name(d.snr_reference), py::arg("rir_smoothing_weight") = d.rir_smoothing_weight,
           py::arg("noise_smoothing_weight") = d.noise_smoothing_weight, py::arg("seed") = d.random_seed,
           py::arg("prefix") = d.prefix)
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
          "What reverberate-data does to copy `copy` of recording `id`: RIR, noise, SNR, noise offset.")
      .def(
          "__call__",
          [](Augmenter& self, const py::handle& speech, double fs, const std::string& id, int copy) {
            const std::vector<float> x = to_samples(speech, "speech");
            std::vector<float> y;
            {
              py::gil_scoped_release release;
              y = self.materialise(x, fs, self.plan(id, copy));
            }
            return to_numpy(std::move(y));
          },
          py::arg("speech"), py::arg("fs"), py::arg("id"), py::arg("copy") = 1,
          "The far-field copy of one utterance (1-D float32).")
      .def(
          "augment",
          [](Augmenter& self, const std::string& id, int copy) {
            std::vector<float> y;
            double fs = 0;
            {
              py::gil_scoped_release release;
              const RecordingPlan plan = self.plan(id, copy);
              AudioInfo info;
              std::vector<std::vector<float>> channels =
                  read_audio_channels(plan.source_rx, &info, "wav.scp: recording '" + id + "'");
              fs = info.sample_rate_hz;
              y = self.materialise(channels.at(0), fs, plan);
            }
            return py::make_tuple(to_numpy(std::move(y)), fs);
          },
          py::arg("id"), py::arg("copy") = 1,
          "Reads the recording's wav.scp entry (path or 'command |') and returns (far-field copy, fs).")
      .def_property_readonly("recordings",
                             [](const Augmenter& a) {
                               std::vector<std::pair<std::string, std::string>> out(a.wav_scp().begin(),
                                                                                    a.wav_scp().end());
                               return out;
                             },
                             "[(id, rxfilename)] in wav.scp (byte) order, reverberate-data's order.")
      .def_property_readonly("num_rirs", [](const Augmenter& a) { return a.sources().rirs.size(); })
      .def_property_readonly("num_noises", [](const Augmenter& a) { return a.sources().noises.size(); })
      .def(py::pickle([](const Augmenter& a) { return settings_tuple(a.settings(), a.wav_scp()); },
                      [](const py::tuple& t) { return augmenter_from_tuple(t); }));
}

}  // namespace tsrir::python
