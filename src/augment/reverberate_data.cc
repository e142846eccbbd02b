#include "augment/reverberate_data.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "augment/augment_plan.h"
#include "augment/augment_sources.h"
#include "augment/plan_renderer.h"
#include "augment/rate_policy.h"
#include "augment/reverberate_stream.h"
#include "augment/sampling.h"
#include "augment/wav_duration.h"
#include "augment/wav_reverberate.h"
#include "io/atomic_output.h"
#include "io/audio_io.h"
#include "io/common_options.h"
#include "io/data_dir.h"
#include "io/kaldi_table.h"
#include "io/owned_output.h"
#include "io/rxfile.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/parallel.h"
#include "util/strings.h"

namespace tsrir {
namespace fs = std::filesystem;

// A pipe's WAV header is enough when it states the size (flac -d, sox): the command is stopped
// after it, as Kaldi's get_reco2dur.sh does; otherwise it is read to the end.
double audio_duration_s(const std::string& rx, const std::string& where) {
  const double seconds = rx_duration_s(rx, false, where);
  if (!(seconds > 0)) throw Error(where + ": zero-length audio");
  return seconds;
}

namespace {

// Kaldi's ids for the tables keyed by recording or utterance; `rename_first_value` also renames
// the first value field (reco2file_and_channel's file id).
void copy_renamed_table(const std::string& in_path, const std::string& out_path, const std::string& prefix,
                        const std::vector<int>& copies, bool rename_first_value) {
  Table table = read_table(in_path);
  std::vector<std::pair<std::string, std::string>> rows;
  for (int copy : copies) {
    for (const TableEntry& e : table.entries) {
      std::string value = e.value;
      if (rename_first_value) {
        std::vector<std::string> fields = split_whitespace(value);
        if (fields.empty()) throw Error(table.where(e) + ": missing value");
        fields[0] = copy_id(fields[0], prefix, copy);
        value.clear();
        for (size_t i = 0; i < fields.size(); ++i) value += (i ? " " : "") + fields[i];
      }
      rows.emplace_back(copy_id(e.key, prefix, copy), value);
    }
  }
  write_table(out_path, std::move(rows));
}

// Each recording's duration: from <in-dir>/reco2dur where it has one (Kaldi's script reads it),
// else measured (a pipe is run once, as Kaldi's get_reco2dur.sh does; the input dir is not written).
std::map<std::string, double> recording_durations(const std::string& in_dir, const DataDir& input, int num_threads) {
  std::map<std::string, double> out;
  std::vector<std::pair<std::string, std::string>> missing;
  for (const auto& [id, rx] : input.wav_scp) {
    auto it = input.reco2dur.find(id);
    if (it != input.reco2dur.end()) out[id] = it->second;
    else missing.emplace_back(id, rx);
  }
  if (missing.empty()) return out;
  if (missing.size() > 100)
    log_info(in_dir + ": measuring the duration of " + std::to_string(missing.size()) +
             " recordings (no reco2dur entry for them)");
  std::vector<double> measured(missing.size());
  parallel_for(missing.size(), std::max(1, num_threads), [&](size_t i) {
    measured[i] = audio_duration_s(missing[i].second, in_dir + "/wav.scp: recording '" + missing[i].first + "'");
  });
  for (size_t i = 0; i < missing.size(); ++i) out[missing[i].first] = measured[i];
  return out;
}

std::string real_program_path(const std::string& program) {
  std::string path = program;
  if (program.find('/') == std::string::npos) {
    const char* env = std::getenv("PATH");
    for (const std::string& dir : split(env ? env : "", ':')) {
      const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
      if (access(candidate.c_str(), X_OK) == 0) {
        path = candidate;
        break;
      }
    }
  }
  std::error_code ec;
  const fs::path real = fs::canonical(path, ec);
  return ec ? program : real.string();
}

bool path_is_inside(const std::string& path, const std::string& dir) {
  const std::string p = absolute_path(path), d = absolute_path(dir);
  return p.size() > d.size() && p.compare(0, d.size(), d) == 0 && p[d.size()] == '/';
}

}  // namespace

bool is_tsrir_pipe_program(const std::string& program) {
  const std::string ours = default_pipe_program();
  return program == ours || real_program_path(program) == real_program_path(ours);
}

std::string default_pipe_program() {
  char buffer[4096];
  ssize_t n = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (n > 0) {
    buffer[n] = '\0';
    fs::path sibling = fs::path(buffer).parent_path() / "wav-reverberate";
    if (access(sibling.c_str(), X_OK) == 0) return sibling.string();
  }
  return "wav-reverberate";
}

const Choices<NoiseStart>& noise_start_choices() {
  static const Choices<NoiseStart> choices = {{"zero", NoiseStart::kZero}, {"random", NoiseStart::kRandom}};
  return choices;
}

const Choices<PointSourceNoiseRir>& point_source_noise_rir_choices() {
  static const Choices<PointSourceNoiseRir> choices = {{"same-room", PointSourceNoiseRir::kSameRoom},
                                                       {"none", PointSourceNoiseRir::kNone}};
  return choices;
}

void ReverberateDataOptions::Register(OptionsItf* opts) {
  opts->Register("rir-set-parameters", &rir_set_parameters,
                 "'[weight,] rir_list': an RIR list (Kaldi rir_list or scp) and its weight; repeatable");
  opts->Register("noise-set-parameters", &noise_set_parameters,
                 "'[weight,] noise_list': a noise list (Kaldi noise_list or scp) and its weight; repeatable");
  opts->Register("num-replications", &num_replications, "number of reverberated copies of each recording");
  opts->Register("prefix", &prefix, "id prefix; copies are <prefix><i>-<id> (forced to rvb for several copies)");
  opts->Register("foreground-snrs", &foreground_snrs,
                 "SNRs (dB) of foreground noises: Kaldi's a:b:c list (cyclic), or lo..hi (uniform; extension)");
  opts->Register("background-snrs", &background_snrs,
                 "SNRs (dB) of background noises: Kaldi's a:b:c list (cyclic), or lo..hi (uniform; extension)");
  opts->Register("speech-rvb-probability", &speech_rvb_probability, "probability of reverberating a recording");
  opts->Register("isotropic-noise-addition-probability", &isotropic_noise_addition_probability,
                 "probability of adding the room's isotropic noise");
  opts->Register("pointsource-noise-addition-probability", &pointsource_noise_addition_probability,
                 "probability of adding point-source noises");
  opts->Register("max-noises-per-minute", &max_noises_per_minute,
                 "at most floor(N * duration / 60) point-source noises per recording (Kaldi)");
  opts->Register("max-noises-per-recording", &max_noises_per_recording,
                 "extension: if > 0, 1..N point-source noises per recording whatever its duration");
  opts->RegisterEnum("noise-start", &noise_start, noise_start_choices(),
                     "zero (Kaldi: background noises extended from their start) or random (extension: from a "
                     "random offset, looped over the whole recording)");
  opts->RegisterEnum("point-source-noise-rir", &point_source_noise_rir, point_source_noise_rir_choices(),
                     "same-room (Kaldi: point sources convolved with an RIR of the recording's room) or none "
                     "(extension)");
  opts->RegisterEnum("pipe-dialect", &pipe_dialect,
                     {{"auto", PipeDialect::kAuto}, {"tsrir", PipeDialect::kTsrir}, {"kaldi", PipeDialect::kKaldi}},
                     "auto (tsrir options in pipes only for our wav-reverberate), tsrir, or kaldi");
  reverb.Register(opts);
  opts->Register("multi-channel-output", &multi_channel_output,
                 "one output channel per channel of the recording's RIR (a microphone array's, e.g. from rir-simulate "
                 "mic=x,y,z;x,y,z): one multichannel recording per utterance (wav-reverberate "
                 "--multi-channel-output=true); a point-source noise goes through each channel of its RIR, an isotropic "
                 "noise needs one channel per RIR channel (a mono one is refused, as Kaldi does), SNR per channel");
  opts->Register("split-channels", &split_channels,
                 "one recording per channel of the recording's RIR instead (the per-channel form): ids <id>.CH<c> "
                 "(c from 1), pipes with wav-reverberate --rir-channel=<c-1> (and --noise-channel=<c-1>), "
                 "reco2file_and_channel '<id> <id> A'; entry c equals channel c of --multi-channel-output, noises "
                 "included");
  opts->Register("include-original-data", &include_original_data, "also keep the originals as copy 0");
  CommonOptions(opts).seed(&random_seed, "every draw");
  opts->Register("sample-rate", &source_sampling_rate_hz,
                 "the data dir's rate in Hz: RIRs and noises are resampled to it (Kaldi's --source-sampling-rate) "
                 "and so is a recording at another rate (in a pipe: tsrir's wav-reverberate --sample-rate); "
                 "0 = the rate of the first recording, and a recording at another rate is an error");
  opts->RegisterAlias("source-sampling-rate", "sample-rate");
  opts->Register("rir-smoothing-weight", &rir_smoothing_weight, "RIR probabilities mixed with uniform (Kaldi)");
  opts->Register("noise-smoothing-weight", &noise_smoothing_weight, "noise probabilities mixed with uniform (Kaldi)");
  opts->Register("write-wavs", &write_wavs, "write 16-bit wavs into this directory instead of pipes");
  opts->Register("pipe-program", &pipe_program,
                 "program called by the pipes (default: wav-reverberate next to this program)");
  CommonOptions(opts).threads(&num_threads, "--write-wavs writes recordings in parallel");
  opts->Register("max-in-memory-duration", &max_in_memory_s,
                 "with --write-wavs: recordings longer than this many seconds are reverberated in passes over the "
                 "file, with memory independent of their length and the same wav (temporaries in the wav dir); "
                 "0 = all");
}

std::string spelled(const std::string& option, OptionSpelling spelling) {
  if (spelling == OptionSpelling::kCommandLine) return "--" + option;
  std::string name = option;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

namespace {

void check_probability(double p, const std::string& option, OptionSpelling spelling) {
  if (p < 0 || p > 1) throw Error(spelled(option, spelling) + " must be in [0, 1]");
}

void check_not_negative(int n, const std::string& option, OptionSpelling spelling) {
  if (n < 0) throw Error(spelled(option, spelling) + " cannot be negative");
}

}  // namespace

ReverberatePlan to_plan(const ReverberateDataOptions& o, OptionSpelling spelling) {
  check_probability(o.speech_rvb_probability, "speech-rvb-probability", spelling);
  check_probability(o.isotropic_noise_addition_probability, "isotropic-noise-addition-probability", spelling);
  check_probability(o.pointsource_noise_addition_probability, "pointsource-noise-addition-probability", spelling);
  check_not_negative(o.max_noises_per_minute, "max-noises-per-minute", spelling);
  check_not_negative(o.max_noises_per_recording, "max-noises-per-recording", spelling);
  if (o.split_channels && o.multi_channel_output) {
    throw Error(spelled("split-channels", spelling) + " and " + spelled("multi-channel-output", spelling) +
                " are two forms of the same data (one recording per channel, or one multichannel recording): "
                "choose one");
  }
  if (o.source_sampling_rate_hz < 0) {
    throw Error(spelled("sample-rate", spelling) + " must be > 0 Hz (or 0: the first recording's), got " +
                format_double(o.source_sampling_rate_hz));
  }
  ReverberatePlan plan;
  plan.sources = load_augment_sources(o.rir_set_parameters, o.noise_set_parameters, o.rir_smoothing_weight,
                                      o.noise_smoothing_weight);
  if (plan.sources.rirs.empty() && plan.sources.noises.empty()) {
    throw Error("nothing to apply: give " + spelled("rir-set-parameters", spelling) + " and/or " +
                spelled("noise-set-parameters", spelling));
  }
  plan.foreground_snrs = SnrSpec::parse(o.foreground_snrs, spelled("foreground-snrs", spelling));
  plan.background_snrs = SnrSpec::parse(o.background_snrs, spelled("background-snrs", spelling));
  PlanOptions& p = plan.planning;
  p.num_replications = o.num_replications;
  p.include_original_data = o.include_original_data;
  p.prefix = o.prefix;
  if (p.prefix.empty() && (o.num_replications > 1 || o.include_original_data)) {
    log_warning("--prefix set to 'rvb' as there is more than one copy of each utterance (as Kaldi does)");
    p.prefix = "rvb";
  }
  p.speech_rvb_probability = o.speech_rvb_probability;
  p.noise.isotropic_noise_addition_probability = o.isotropic_noise_addition_probability;
  p.noise.pointsource_noise_addition_probability = o.pointsource_noise_addition_probability;
  p.noise.max_noises_per_minute = o.max_noises_per_minute;
  p.noise.max_noises_per_recording = o.max_noises_per_recording;
  p.noise.random_noise_start = o.noise_start == NoiseStart::kRandom;
  p.noise.point_source_noise_rir = o.point_source_noise_rir == PointSourceNoiseRir::kSameRoom;
  p.random_seed = o.random_seed;
  plan.reverb = o.reverb;
  plan.multi_channel_output = o.multi_channel_output;
  plan.split_channels = o.split_channels;
  plan.sample_rate_hz = o.source_sampling_rate_hz;
  return plan;
}

namespace {

// The data dir's recordings, every copy planned; looped noises' offsets resolved in seconds
// (each looped noise's duration measured once).
std::vector<RecordingPlan> plan_copies(const std::string& in_dir, const DataDir& input, const ReverberatePlan& plan,
                                       int num_threads) {
  const std::map<std::string, double> durations = recording_durations(in_dir, input, num_threads);
  std::vector<RecordingPlan> plans = plan_recordings(input.wav_scp, durations, plan.sources, plan.foreground_snrs,
                                                     plan.background_snrs, plan.planning);
  std::map<long, double> noise_duration_s;
  for (const RecordingPlan& recording : plans) {
    for (const PlannedNoise& noise : recording.noises) {
      if (noise.loop && !noise_duration_s.count(noise.noise)) {
        const NoiseChoice& n = plan.sources.noises[static_cast<size_t>(noise.noise)];
        noise_duration_s[noise.noise] = audio_duration_s(n.rxfilename, n.where + " (noise '" + n.id + "')");
      }
    }
  }
  resolve_noise_offsets(noise_duration_s, &plans);
  return plans;
}

// Kaldi/CHiME's id suffix of channel `channel` (from 0) of a split recording.
std::string channel_suffix(int channel) { return ".CH" + std::to_string(channel + 1); }

// --split-channels: each reverberated plan becomes one plan per channel of its RIR (each RIR's
// channels read once from its header), ids suffixed; plans without an RIR stay as they are.
std::vector<RecordingPlan> split_into_channels(std::vector<RecordingPlan> plans, const AugmentSources& sources) {
  std::map<long, int> rir_channels;
  std::vector<RecordingPlan> out;
  for (RecordingPlan& recording : plans) {
    if (recording.rir < 0) {
      out.push_back(std::move(recording));
      continue;
    }
    auto it = rir_channels.find(recording.rir);
    if (it == rir_channels.end()) {
      const RirChoice& rir = sources.rirs[static_cast<size_t>(recording.rir)];
      const int channels = rx_audio_header(rir.rxfilename, false, rir.where + " (RIR '" + rir.id + "')").channels;
      it = rir_channels.emplace(recording.rir, channels).first;
    }
    for (int c = 0; c < it->second; ++c) {
      RecordingPlan one = recording;
      one.new_id += channel_suffix(c);
      one.rir_channel = c;
      out.push_back(std::move(one));
    }
  }
  return out;
}

// Multichannel far-field data with noises (--multi-channel-output or --split-channels), checked
// before anything is written, from the files' headers: each reverberated recording with an
// N-channel RIR needs an N-channel RIR for each point-source noise (the same array in the same
// room) and N channels in each noise added without an RIR (isotropic, or --point-source-noise-rir
// none): wav-reverberate --multi-channel-output's rule, which Kaldi's binary asserts. A mono
// background noise is refused, as Kaldi refuses it, rather than copied to every microphone (which
// would make a fully coherent "diffuse" noise). Returns the channel count of each noise added
// without an RIR to a reverberated recording (noise index -> channels), which the pipes for Kaldi's
// program make channel by channel (PipeOptions::noise_channels).
std::map<long, int> check_array_noise_channels(const std::vector<RecordingPlan>& plans, const AugmentSources& sources) {
  std::map<std::string, int> channels_of;
  std::map<long, int> unreverberated;
  auto channels = [&](const std::string& rx, const std::string& where) {
    auto it = channels_of.find(rx);
    if (it == channels_of.end()) it = channels_of.emplace(rx, rx_audio_header(rx, false, where).channels).first;
    return it->second;
  };
  for (const RecordingPlan& recording : plans) {
    if (recording.rir < 0 || recording.noises.empty()) continue;
    const RirChoice& rir = sources.rirs[static_cast<size_t>(recording.rir)];
    const int n = channels(rir.rxfilename, rir.where + " (RIR '" + rir.id + "')");
    for (const PlannedNoise& noise : recording.noises) {
      const NoiseChoice& choice = sources.noises[static_cast<size_t>(noise.noise)];
      const RirChoice* noise_rir = noise.rir >= 0 ? &sources.rirs[static_cast<size_t>(noise.rir)] : nullptr;
      const std::string where = noise_rir ? noise_rir->where + " (RIR '" + noise_rir->id + "' of the point-source noise '" +
                                                choice.id + "')"
                                          : choice.where + " (noise '" + choice.id + "', added without an RIR)";
      const int k = channels(noise_rir ? noise_rir->rxfilename : choice.rxfilename, where);
      if (k != n)
        throw Error(where + ": has " + std::to_string(k) + " channel(s) but recording '" + recording.new_id +
                    "' is reverberated with RIR '" + rir.id + "' of " + std::to_string(n) + ": multichannel output " +
                    "needs one noise channel per RIR channel (a point source's RIR from the same array, an isotropic " +
                    "noise recorded with as many microphones), as wav-reverberate --multi-channel-output does");
      if (!noise_rir) unreverberated[noise.noise] = k;
    }
  }
  return unreverberated;
}

// (copy, input recording id) -> the suffixes of its output recordings ("" unless split).
using ChannelSuffixes = std::map<std::pair<int, std::string>, std::vector<std::string>>;
ChannelSuffixes channel_suffixes(const std::vector<RecordingPlan>& plans) {
  ChannelSuffixes suffixes;
  for (const RecordingPlan& recording : plans) {
    suffixes[{recording.copy, recording.source_id}].push_back(
        recording.rir_channel >= 0 ? channel_suffix(recording.rir_channel) : std::string());
  }
  return suffixes;
}

// wav.scp of pipes that regenerate each recording. Fails now, not inside a feature-extraction job,
// on RIR files that cannot be read and on recording files at another rate that the pipe cannot
// resample (rate_policy.h).
std::map<std::string, std::string> pipe_wav_scp(const std::vector<RecordingPlan>& plans, const ReverberatePlan& plan,
                                                 const std::string& in_dir, const DataDir& input,
                                                 const DirSampleRate& dir_rate, const ReverberateDataOptions& options,
                                                 const std::map<long, int>& unreverberated_noise_channels) {
  std::set<long> used_rirs;
  for (const RecordingPlan& recording : plans) {
    if (recording.rir >= 0) used_rirs.insert(recording.rir);
    for (const PlannedNoise& noise : recording.noises) {
      if (noise.rir >= 0) used_rirs.insert(noise.rir);
    }
  }
  for (long r : used_rirs) {
    const RirChoice& rir = plan.sources.rirs[static_cast<size_t>(r)];
    if (!is_pipe_rxfilename(rir.rxfilename)) audio_duration_s(rir.rxfilename, rir.where + " (RIR '" + rir.id + "')");
  }
  PipeOptions pipe;
  pipe.program = options.pipe_program.empty() ? default_pipe_program() : options.pipe_program;
  pipe.reverb = plan.reverb;
  pipe.multi_channel_output = plan.multi_channel_output;
  pipe.tsrir_extensions = options.pipe_dialect == PipeDialect::kTsrir ||
                          (options.pipe_dialect == PipeDialect::kAuto && is_tsrir_pipe_program(pipe.program));
  if (pipe.tsrir_extensions && dir_rate.given()) pipe.sample_rate_hz = dir_rate.rate_hz();
  if (plan.multi_channel_output && !pipe.tsrir_extensions) pipe.noise_channels = unreverberated_noise_channels;
  check_recording_rates(input.wav_scp, dir_rate, pipe.sample_rate_hz > 0, in_dir, options.num_threads);
  std::map<std::string, std::string> wav_scp;
  for (const RecordingPlan& recording : plans) wav_scp[recording.new_id] = format_pipe(recording, plan.sources, pipe);
  return wav_scp;
}

// "wrote N/M wavs (R per second)" on stderr every 5 s and at the end.
class WavProgress {
 public:
  explicit WavProgress(size_t total) : total_(total), started_(std::chrono::steady_clock::now()), last_(started_) {}
  void one_done() {
    const size_t finished = ++done_;
    std::lock_guard<std::mutex> lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ > std::chrono::seconds(5) || finished == total_) {
      last_ = now;
      const double elapsed = std::chrono::duration<double>(now - started_).count();
      log_info("wrote " + std::to_string(finished) + "/" + std::to_string(total_) + " wavs (" +
               format_double(finished / std::max(elapsed, 1e-9), 4) + " per second)");
    }
  }

 private:
  const size_t total_;
  std::atomic<size_t> done_{0};
  const std::chrono::steady_clock::time_point started_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_;
};

// One recording's wav at `wav_path`, at the data dir's rate (rate_policy.h), in memory or, beyond
// --max-in-memory-duration, in passes over the file; returns the samples clipped to 16 bits.
long long write_one_wav(const RecordingPlan& recording, const std::string& in_dir, const std::string& wav_path,
                        const ReverberateDataOptions& options, const DirSampleRate& dir_rate, PlanRenderer& renderer) {
  if (recording.new_id.find('/') != std::string::npos)
    throw Error("recording id '" + recording.new_id + "' contains '/', which cannot name a wav file");
  const std::string where = in_dir + "/wav.scp: recording '" + recording.source_id + "'";
  SpeechInput speech = open_speech_input(recording.source_rx, options.max_in_memory_s, wav_path + ".input", where);
  const AudioInfo speech_info = speech.on_disk() ? probe_audio(speech.path) : speech.info;
  const double rate = dir_rate.rate_hz();
  if (!speech.on_disk()) {
    speech.channels = {dir_rate.speech_at_rate(std::move(speech.channels), speech_info.sample_rate_hz, where)};
  } else if (!dir_rate.accepts(speech_info.sample_rate_hz, where) || speech_info.channels > 1) {
    throw Error(where + ": longer than --max-in-memory-duration and at " + format_double(speech_info.sample_rate_hz) +
                " Hz with " + std::to_string(speech_info.channels) + " channel(s): only a mono recording at the " +
                "data dir's rate is reverberated in passes (resample or split it first)");
  }
  long long clipped = 0;
  if (!speech.on_disk()) {
    const std::vector<std::vector<float>> result =
        options.multi_channel_output ? renderer.render_channels(speech.channels.at(0), rate, recording)
                                     : std::vector<std::vector<float>>{renderer.render(speech.channels.at(0), rate, recording)};
    speech.channels.clear();
    AudioWriteOptions write_options;
    write_options.clipped_samples = &clipped;
    write_wav_channels(wav_path, result, rate, write_options);
    return clipped;
  }
  log_info(where + ": longer than " + format_double(options.max_in_memory_s) +
           " s: reverberated in passes over the file (memory independent of its length)");
  // --multi-channel-output: one stream channel per RIR channel, else one (both kept alive while
  // streaming).
  const std::shared_ptr<const PlanRenderer::RirChannels> array =
      options.multi_channel_output ? renderer.rir_channels(recording.rir, rate) : nullptr;
  std::shared_ptr<const PreparedRir> rir;
  std::vector<StreamChannel> channels(array ? array->size() : 1);
  if (array) {
    for (size_t c = 0; c < array->size(); ++c) {
      channels[c].rir = (*array)[c].get();
      channels[c].additive = renderer.additive_signals(recording, rate, static_cast<int>(c));
    }
  } else {
    rir = renderer.speech_rir(recording, rate);
    channels[0].rir = rir.get();
    channels[0].additive = renderer.additive_signals(recording, rate, recording.rir >= 0 ? recording.rir_channel : -1);
  }
  StreamSettings settings;
  settings.temp_base = wav_path + ".spill";
  return reverberate_stream(speech.path, where, speech.rx, 0, channels, renderer.reverb(), wav_path, settings)
      .clipped_samples;
}

// --write-wavs: every recording's wav, written into the wav dir's staging area (committed with the
// data dir); returns wav.scp.
std::map<std::string, std::string> write_wavs(const std::vector<RecordingPlan>& plans, const ReverberatePlan& plan,
                                              const std::string& in_dir, const ReverberateDataOptions& options,
                                              const DirSampleRate& dir_rate, const OwnedOutputDir& wav_dir) {
  std::vector<std::string> wav_names;
  for (const RecordingPlan& recording : plans) wav_names.push_back(recording.new_id + ".wav");
  wav_dir.check_names(wav_names);
  PlanRenderer renderer(plan.sources, plan.reverb);
  WavProgress progress(plans.size());
  std::atomic<long long> clipped{0};
  parallel_for(plans.size(), options.num_threads, [&](size_t i) {
    clipped += write_one_wav(plans[i], in_dir, wav_dir.path() + "/" + plans[i].new_id + ".wav", options, dir_rate,
                             renderer);
    progress.one_done();
  });
  if (clipped > 0)
    log_warning("clipped " + std::to_string(clipped.load()) + " samples in total; consider --normalize-output=true");
  const std::string final_wav_dir = absolute_path(options.write_wavs);
  std::map<std::string, std::string> wav_scp;
  for (const RecordingPlan& recording : plans) wav_scp[recording.new_id] = final_wav_dir + "/" + recording.new_id + ".wav";
  return wav_scp;
}

// The copies' utterance tables (Kaldi's ids): utt2spk, text, utt2uniq (new id -> original), segments;
// with --split-channels one utterance per channel of its recording, same speaker.
void copy_utterance_tables(const DataDir& input, const std::string& prefix, const std::vector<int>& copies,
                           const ChannelSuffixes& suffixes, DataDir* output) {
  const std::vector<std::string> unsplit{""};
  for (int copy : copies) {
    for (const auto& [utt, spk] : input.utt2spk) {
      auto seg = input.segments.find(utt);
      const std::string& recording = seg != input.segments.end() ? seg->second.recording_id : utt;
      auto channels = suffixes.find({copy, recording});
      for (const std::string& suffix : channels != suffixes.end() ? channels->second : unsplit) {
        const std::string new_utt = copy_id(utt, prefix, copy) + suffix;
        output->utt2spk[new_utt] = copy_id(spk, prefix, copy);
        auto text = input.text.find(utt);
        if (text != input.text.end()) output->text[new_utt] = text->second;
        auto uniq = input.utt2uniq.find(utt);
        output->utt2uniq[new_utt] = uniq != input.utt2uniq.end() ? uniq->second : utt;
        if (seg != input.segments.end()) {
          Segment s = seg->second;
          s.recording_id = copy_id(s.recording_id, prefix, copy) + suffix;
          output->segments[new_utt] = s;
        }
      }
    }
  }
}

// Writes the data dir into `out_dir` (the staging dir) and checks it as validate_data_dir.sh would.
// With --split-channels, reco2file_and_channel names each channel's recording as its own file
// (side A), whatever the input had.
void write_checked_data_dir(const std::string& in_dir, const std::string& out_dir, const DataDir& output,
                            const std::string& prefix, const std::vector<int>& copies, bool has_text,
                            bool split_channels) {
  write_data_dir(out_dir, output);
  if (split_channels) {
    std::vector<std::pair<std::string, std::string>> rows;
    for (const auto& [id, rx] : output.wav_scp) rows.emplace_back(id, id + " A");
    write_table(out_dir + "/reco2file_and_channel", std::move(rows));
  } else if (fs::exists(in_dir + "/reco2file_and_channel"))
    copy_renamed_table(in_dir + "/reco2file_and_channel", out_dir + "/reco2file_and_channel", prefix, copies, true);
  if (fs::exists(in_dir + "/vad.scp"))
    copy_renamed_table(in_dir + "/vad.scp", out_dir + "/vad.scp", prefix, copies, false);
  std::vector<std::string> problems = validate_data_dir(out_dir, has_text);
  if (!problems.empty()) {
    std::string message = "the output data dir failed validation:";
    for (const std::string& p : problems) message += "\n  " + p;
    throw Error(message);
  }
}

}  // namespace

ReverberateDataSummary reverberate_data_dir(const std::string& in_dir, const std::string& out_dir,
                                            const ReverberateDataOptions& options) {
  if (absolute_path(in_dir) == absolute_path(out_dir)) throw Error("input and output data dirs are the same");
  const ReverberatePlan plan = to_plan(options, OptionSpelling::kCommandLine);
  const DataDir input = read_data_dir(in_dir);
  if (input.wav_scp.empty()) throw Error(in_dir + "/wav.scp: no recordings");
  std::vector<RecordingPlan> plans = plan_copies(in_dir, input, plan, options.num_threads);
  if (plan.split_channels) plans = split_into_channels(std::move(plans), plan.sources);
  std::map<long, int> unreverberated_noise_channels;  // of arrays: check_array_noise_channels
  if (plan.split_channels || plan.multi_channel_output)
    unreverberated_noise_channels = check_array_noise_channels(plans, plan.sources);
  const auto& [first_id, first_rx] = *input.wav_scp.begin();
  const DirSampleRate dir_rate(plan.sample_rate_hz, first_id, first_rx, in_dir + "/wav.scp: recording '" + first_id + "'");

  // Every input, so that no output lands on one (io/owned_output.h).
  InputLedger& inputs = *run_inputs();
  inputs.add(in_dir);
  for (const auto& [id, rx] : input.wav_scp) inputs.add(rx);
  for (const RirChoice& r : plan.sources.rirs) inputs.add(r.rxfilename);
  for (const NoiseChoice& n : plan.sources.noises) inputs.add(n.rxfilename);
  OwnedOutputDir out(out_dir);
  DataDir output;
  std::unique_ptr<OwnedOutputDir> wav_dir;
  if (options.write_wavs.empty()) {
    output.wav_scp = pipe_wav_scp(plans, plan, in_dir, input, dir_rate, options, unreverberated_noise_channels);
  } else {
    if (path_is_inside(out_dir, absolute_path(options.write_wavs)))
      throw Error("--write-wavs directory " + options.write_wavs + " must not contain the output data dir");
    // The wavs belong to this data dir: another data dir's wavs in a shared --write-wavs directory
    // are never replaced (it would point at different audio) unless --overwrite.
    wav_dir = std::make_unique<OwnedOutputDir>(options.write_wavs, out_dir);
    output.wav_scp = write_wavs(plans, plan, in_dir, options, dir_rate, *wav_dir);
  }

  std::vector<int> copies;
  for (int c = options.include_original_data ? 0 : 1; c <= options.num_replications; ++c) copies.push_back(c);
  const std::string& prefix = plan.planning.prefix;
  copy_utterance_tables(input, prefix, copies, channel_suffixes(plans), &output);
  // Shifted outputs keep the input's length, so its durations carry over to the new ids.
  if (options.reverb.shift_output) {
    for (const RecordingPlan& recording : plans) output.reco2dur[recording.new_id] = recording.duration_s;
  }
  write_checked_data_dir(in_dir, out.path(), output, prefix, copies, !input.text.empty(), plan.split_channels);
  if (wav_dir) wav_dir->commit();
  out.commit();

  ReverberateDataSummary summary;
  for (const RecordingPlan& recording : plans) {
    summary.reverberated += recording.rir >= 0;
    summary.with_noise += !recording.noises.empty();
  }
  summary.recordings = output.wav_scp.size();
  summary.utterances = output.utt2spk.size();
  log_info(out_dir + ": " + std::to_string(summary.recordings) + " recordings (" + std::to_string(summary.reverberated) +
           " reverberated, " + std::to_string(summary.with_noise) + " with noise), " +
           std::to_string(summary.utterances) + " utterances");
  return summary;
}

}  // namespace tsrir
