#include "augment/reverberate_data.h"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "augment/augment_plan.h"
#include "augment/augment_sources.h"
#include "augment/noise_signal.h"
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
namespace {

namespace fs = std::filesystem;

// Loads each (item, sample rate) once, on first use, from whichever thread needs it first;
// other threads wanting the same item wait for that load instead of repeating it.
template <typename T>
class LoadOnceCache {
 public:
  std::shared_ptr<const T> get(const std::pair<long, double>& key, const std::function<T()>& load) {
    std::shared_ptr<Slot> slot;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto& s = slots_[key];
      if (!s) s = std::make_shared<Slot>();
      slot = s;
    }
    std::call_once(slot->once, [&] {
      try {
        slot->value = std::make_shared<const T>(load());
      } catch (...) {
        slot->error = std::current_exception();
      }
    });
    if (slot->error) std::rethrow_exception(slot->error);
    return slot->value;
  }

 private:
  struct Slot {
    std::once_flag once;
    std::shared_ptr<const T> value;
    std::exception_ptr error;
  };
  std::mutex mutex_;
  std::map<std::pair<long, double>, std::shared_ptr<Slot>> slots_;
};

}  // namespace

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
  opts->Register("noise-start", &noise_start,
                 "zero (Kaldi: background noises extended from their start) or random (extension: from a random "
                 "offset, looped over the whole recording)");
  opts->Register("point-source-noise-rir", &point_source_noise_rir,
                 "same-room (Kaldi: point sources convolved with an RIR of the recording's room) or none (extension)");
  opts->Register("pipe-dialect", &pipe_dialect,
                 "auto (tsrir options in pipes only for our wav-reverberate), tsrir, or kaldi");
  reverb.Register(opts);
  opts->Register("include-original-data", &include_original_data, "also keep the originals as copy 0");
  CommonOptions(opts).seed(&random_seed, "every draw");
  opts->Register("source-sampling-rate", &source_sampling_rate_hz,
                 "if > 0, the speech's rate in Hz (checked with --write-wavs; RIRs and noises are always resampled "
                 "to the speech's rate)");
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

ReverberateDataSummary reverberate_data_dir(const std::string& in_dir, const std::string& out_dir,
                                            const ReverberateDataOptions& options) {
  if (options.speech_rvb_probability < 0 || options.speech_rvb_probability > 1)
    throw Error("--speech-rvb-probability must be in [0, 1]");
  if (options.isotropic_noise_addition_probability < 0 || options.isotropic_noise_addition_probability > 1)
    throw Error("--isotropic-noise-addition-probability must be in [0, 1]");
  if (options.pointsource_noise_addition_probability < 0 || options.pointsource_noise_addition_probability > 1)
    throw Error("--pointsource-noise-addition-probability must be in [0, 1]");
  if (options.max_noises_per_minute < 0) throw Error("--max-noises-per-minute cannot be negative");
  if (options.max_noises_per_recording < 0) throw Error("--max-noises-per-recording cannot be negative");
  if (options.noise_start != "random" && options.noise_start != "zero")
    throw Error("--noise-start must be random or zero, got '" + options.noise_start + "'");
  if (options.point_source_noise_rir != "same-room" && options.point_source_noise_rir != "none")
    throw Error("--point-source-noise-rir must be same-room or none, got '" + options.point_source_noise_rir + "'");
  if (options.pipe_dialect != "auto" && options.pipe_dialect != "tsrir" && options.pipe_dialect != "kaldi")
    throw Error("--pipe-dialect must be auto, tsrir or kaldi, got '" + options.pipe_dialect + "'");
  if (absolute_path(in_dir) == absolute_path(out_dir)) throw Error("input and output data dirs are the same");

  const DataDir input = read_data_dir(in_dir);
  if (input.wav_scp.empty()) throw Error(in_dir + "/wav.scp: no recordings");
  const AugmentSources sources = load_augment_sources(options.rir_set_parameters, options.noise_set_parameters,
                                                      options.rir_smoothing_weight, options.noise_smoothing_weight);
  if (sources.rirs.empty() && sources.noises.empty())
    throw Error("nothing to apply: give --rir-set-parameters and/or --noise-set-parameters");
  const SnrSpec foreground_snrs = SnrSpec::parse(options.foreground_snrs, "--foreground-snrs");
  const SnrSpec background_snrs = SnrSpec::parse(options.background_snrs, "--background-snrs");
  const std::map<std::string, double> durations = recording_durations(in_dir, input, options.num_threads);

  PlanOptions plan_options;
  plan_options.num_replications = options.num_replications;
  plan_options.include_original_data = options.include_original_data;
  plan_options.prefix = options.prefix;
  if (plan_options.prefix.empty() && (options.num_replications > 1 || options.include_original_data)) {
    log_warning("--prefix set to 'rvb' as there is more than one copy of each utterance (as Kaldi does)");
    plan_options.prefix = "rvb";
  }
  plan_options.speech_rvb_probability = options.speech_rvb_probability;
  plan_options.noise.isotropic_noise_addition_probability = options.isotropic_noise_addition_probability;
  plan_options.noise.pointsource_noise_addition_probability = options.pointsource_noise_addition_probability;
  plan_options.noise.max_noises_per_minute = options.max_noises_per_minute;
  plan_options.noise.max_noises_per_recording = options.max_noises_per_recording;
  plan_options.noise.random_noise_start = options.noise_start == "random";
  plan_options.noise.point_source_noise_rir = options.point_source_noise_rir == "same-room";
  plan_options.random_seed = options.random_seed;
  std::vector<RecordingPlan> plans =
      plan_recordings(input.wav_scp, durations, sources, foreground_snrs, background_snrs, plan_options);

  std::map<long, double> noise_duration_s;
  std::set<long> used_rirs;
  for (const RecordingPlan& plan : plans) {
    for (const PlannedNoise& noise : plan.noises) {
      if (noise.loop && !noise_duration_s.count(noise.noise)) {
        const NoiseChoice& n = sources.noises[static_cast<size_t>(noise.noise)];
        noise_duration_s[noise.noise] = audio_duration_s(n.rxfilename, n.where + " (noise '" + n.id + "')");
      }
      if (noise.rir >= 0) used_rirs.insert(noise.rir);
    }
    if (plan.rir >= 0) used_rirs.insert(plan.rir);
  }
  resolve_noise_offsets(noise_duration_s, &plans);

  // Every input, so that no output lands on one (io/owned_output.h).
  note_input(in_dir);
  for (const auto& [id, rx] : input.wav_scp) note_input(rx);
  for (const RirChoice& r : sources.rirs) note_input(r.rxfilename);
  for (const NoiseChoice& n : sources.noises) note_input(n.rxfilename);
  OwnedOutputDir out(out_dir);
  DataDir output;
  ReverberateDataSummary summary;
  for (const RecordingPlan& plan : plans) {
    summary.reverberated += plan.rir >= 0;
    summary.with_noise += !plan.noises.empty();
  }

  std::unique_ptr<OwnedOutputDir> wav_dir;
  if (options.write_wavs.empty()) {
    // Pipes: fail now, not inside a feature-extraction job, on RIR files that cannot be read.
    for (long r : used_rirs) {
      const RirChoice& rir = sources.rirs[static_cast<size_t>(r)];
      if (!is_pipe_rxfilename(rir.rxfilename)) audio_duration_s(rir.rxfilename, rir.where + " (RIR '" + rir.id + "')");
    }
    PipeOptions pipe;
    pipe.program = options.pipe_program.empty() ? default_pipe_program() : options.pipe_program;
    pipe.reverb = options.reverb;
    pipe.tsrir_extensions = options.pipe_dialect == "tsrir" ||
                            (options.pipe_dialect == "auto" && is_tsrir_pipe_program(pipe.program));
    for (const RecordingPlan& plan : plans) output.wav_scp[plan.new_id] = format_pipe(plan, sources, pipe);
  } else {
    const std::string final_wav_dir = absolute_path(options.write_wavs);
    if (path_is_inside(out_dir, final_wav_dir))
      throw Error("--write-wavs directory " + options.write_wavs + " must not contain the output data dir");
    // The wavs belong to this data dir: another data dir's wavs in a shared --write-wavs directory
    // are never replaced (it would point at different audio) unless --overwrite.
    wav_dir = std::make_unique<OwnedOutputDir>(options.write_wavs, out_dir);
    std::vector<std::string> wav_names;
    for (const RecordingPlan& plan : plans) wav_names.push_back(plan.new_id + ".wav");
    wav_dir->check_names(wav_names);
    const std::string temp_wav_dir = wav_dir->path();

    const ReverbOptions& reverb = options.reverb;

    LoadOnceCache<PreparedRir> rir_cache;
    LoadOnceCache<std::vector<float>> noise_cache;
    std::atomic<size_t> done{0};
    std::atomic<long long> clipped{0};
    const auto started = std::chrono::steady_clock::now();
    std::mutex progress_mutex;
    auto last_report = started;
    parallel_for(plans.size(), options.num_threads, [&](size_t i) {
      const RecordingPlan& plan = plans[i];
      if (plan.new_id.find('/') != std::string::npos)
        throw Error("recording id '" + plan.new_id + "' contains '/', which cannot name a wav file");
      const std::string where = in_dir + "/wav.scp: recording '" + plan.source_id + "'";
      const std::string wav_path = temp_wav_dir + "/" + plan.new_id + ".wav";
      SpeechInput speech = open_speech_input(plan.source_rx, options.max_in_memory_s, wav_path + ".input", where);
      const double rate = speech.on_disk() ? probe_audio(speech.path).sample_rate_hz : speech.info.sample_rate_hz;
      if (options.source_sampling_rate_hz > 0 && rate != options.source_sampling_rate_hz)
        throw Error(where + ": sample rate " + format_double(rate) + " Hz, but --source-sampling-rate is " +
                    format_double(options.source_sampling_rate_hz));
      std::shared_ptr<const PreparedRir> rir;
      auto load_rir = [&](long index) {
        const RirChoice& choice = sources.rirs[static_cast<size_t>(index)];
        return rir_cache.get({index, rate}, [&] {
          std::vector<std::vector<float>> ch =
              read_channels_at_rate(choice.rxfilename, rate, choice.where + " (RIR '" + choice.id + "')");
          return PreparedRir(std::move(ch.at(0)), rate);
        });
      };
      if (plan.rir >= 0) rir = load_rir(plan.rir);
      std::vector<AdditiveSignal> additive;
      for (const PlannedNoise& planned : plan.noises) {
        const NoiseChoice& choice = sources.noises[static_cast<size_t>(planned.noise)];
        std::shared_ptr<const std::vector<float>> noise = noise_cache.get({planned.noise, rate}, [&] {
          std::vector<std::vector<float>> ch =
              read_channels_at_rate(choice.rxfilename, rate, choice.where + " (noise '" + choice.id + "')");
          return std::move(ch.at(0));
        });
        std::shared_ptr<const PreparedRir> noise_rir;
        if (planned.rir >= 0) noise_rir = load_rir(planned.rir);
        additive.push_back(planned_noise_signal(planned, noise, noise_rir.get(), rate));
      }
      long long clipped_here = 0;
      if (!speech.on_disk()) {
        Signal result;
        result.id = plan.new_id;
        result.sample_rate_hz = rate;
        result.samples = reverberate_channel(speech.channels.at(0), rate, rir.get(), additive, reverb);
        speech.channels.clear();
        AudioWriteOptions write_options;
        write_options.clipped_samples = &clipped_here;
        write_wav(wav_path, result, write_options);
      } else {
        log_info(where + ": longer than " + format_double(options.max_in_memory_s) +
                 " s: reverberated in passes over the file (memory independent of its length)");
        StreamChannel channel;
        channel.rir = rir.get();
        channel.additive = additive;
        StreamSettings settings;
        settings.temp_base = wav_path + ".spill";
        clipped_here = reverberate_stream(speech.path, where, speech.rx, 0, {channel}, reverb, wav_path, settings)
                           .clipped_samples;
      }
      clipped += clipped_here;
      const size_t finished = ++done;
      std::lock_guard<std::mutex> lock(progress_mutex);
      const auto now = std::chrono::steady_clock::now();
      if (now - last_report > std::chrono::seconds(5) || finished == plans.size()) {
        last_report = now;
        const double elapsed = std::chrono::duration<double>(now - started).count();
        log_info("wrote " + std::to_string(finished) + "/" + std::to_string(plans.size()) + " wavs (" +
                 format_double(finished / std::max(elapsed, 1e-9), 4) + " per second)");
      }
    });
    if (clipped > 0)
      log_warning("clipped " + std::to_string(clipped.load()) + " samples in total; consider --normalize-output=true");
    for (const RecordingPlan& plan : plans) output.wav_scp[plan.new_id] = final_wav_dir + "/" + plan.new_id + ".wav";
  }

  std::vector<int> copies;
  for (int c = options.include_original_data ? 0 : 1; c <= options.num_replications; ++c) copies.push_back(c);
  const std::string& prefix = plan_options.prefix;
  for (int copy : copies) {
    for (const auto& [utt, spk] : input.utt2spk) {
      const std::string new_utt = copy_id(utt, prefix, copy);
      output.utt2spk[new_utt] = copy_id(spk, prefix, copy);
      auto text = input.text.find(utt);
      if (text != input.text.end()) output.text[new_utt] = text->second;
      auto uniq = input.utt2uniq.find(utt);
      output.utt2uniq[new_utt] = uniq != input.utt2uniq.end() ? uniq->second : utt;
      auto seg = input.segments.find(utt);
      if (seg != input.segments.end()) {
        Segment s = seg->second;
        s.recording_id = copy_id(s.recording_id, prefix, copy);
        output.segments[new_utt] = s;
      }
    }
  }
  // Shifted outputs keep the input's length, so its durations carry over to the new ids.
  if (options.reverb.shift_output) {
    for (const RecordingPlan& plan : plans) output.reco2dur[plan.new_id] = plan.duration_s;
  }
  write_data_dir(out.path(), output);
  if (fs::exists(in_dir + "/reco2file_and_channel"))
    copy_renamed_table(in_dir + "/reco2file_and_channel", out.path() + "/reco2file_and_channel", prefix, copies, true);
  if (fs::exists(in_dir + "/vad.scp"))
    copy_renamed_table(in_dir + "/vad.scp", out.path() + "/vad.scp", prefix, copies, false);

  std::vector<std::string> problems = validate_data_dir(out.path(), !input.text.empty());
  if (!problems.empty()) {
    std::string message = "the output data dir failed validation:";
    for (const std::string& p : problems) message += "\n  " + p;
    throw Error(message);
  }
  if (wav_dir) wav_dir->commit();
  out.commit();
  summary.recordings = output.wav_scp.size();
  summary.utterances = output.utt2spk.size();
  log_info(out_dir + ": " + std::to_string(summary.recordings) + " recordings (" + std::to_string(summary.reverberated) +
           " reverberated, " + std::to_string(summary.with_noise) + " with noise), " +
           std::to_string(summary.utterances) + " utterances");
  return summary;
}

}  // namespace tsrir
