#include "augment/augment_plan.h"

#include <cmath>
#include <cstdio>

#include "io/rxfile.h"
#include "io/shell.h"
#include "util/error.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir {

std::string copy_id(const std::string& id, const std::string& prefix, int copy) {
  if (prefix.empty()) return id;
  return prefix + std::to_string(copy) + "-" + id;
}

double pipe_rounded(double value) { return std::round(value * 1e6) / 1e6; }

std::string pipe_number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", pipe_rounded(value));
  std::string s = buffer;
  // "1.500000" -> "1.5", "3.000000" -> "3"
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::vector<RecordingPlan> plan_recordings(const std::map<std::string, std::string>& wav_scp,
                                           const std::map<std::string, double>& duration_s,
                                           const AugmentSources& sources, const SnrSpec& foreground_snrs,
                                           const SnrSpec& background_snrs, const PlanOptions& options) {
  if (options.num_replications < 1) throw Error("--num-replications must be at least 1");
  std::vector<double> rir_weights;
  for (const auto& r : sources.rirs) rir_weights.push_back(r.probability);
  SnrSequence foreground(foreground_snrs, Rng::for_item(options.random_seed, "foreground-snrs"));
  SnrSequence background(background_snrs, Rng::for_item(options.random_seed, "background-snrs"));
  std::vector<RecordingPlan> plans;
  const int first_copy = options.include_original_data ? 0 : 1;
  for (int copy = first_copy; copy <= options.num_replications; ++copy) {
    for (const auto& [id, rx] : wav_scp) {
      RecordingPlan plan;
      plan.copy = copy;
      plan.source_id = id;
      plan.new_id = copy_id(id, options.prefix, copy);
      plan.source_rx = rx;
      auto d = duration_s.find(id);
      if (d == duration_s.end()) throw Error("internal: no duration for recording '" + id + "'");
      plan.duration_s = d->second;
      Rng rng = Rng::for_item(options.random_seed, std::to_string(copy) + "/" + id);
      const double u_rir = rng.uniform();
      const double u_rvb = rng.uniform();
      if (!sources.rirs.empty()) {
        const long rir = static_cast<long>(weighted_index(rir_weights, u_rir));
        plan.room = sources.rirs[static_cast<size_t>(rir)].room_id;
        if (u_rvb < options.speech_rvb_probability) plan.rir = rir;
      }
      NoisePlanContext context{sources, plan.room, plan.duration_s, options.noise, rng, foreground, background};
      for (const auto& type : noise_types()) type->plan(context, &plan.noises);
      if (copy == 0) {  // the original: Kaldi draws (and advances its SNR lists) but applies nothing
        plan.rir = -1;
        plan.noises.clear();
      }
      plans.push_back(std::move(plan));
    }
  }
  return plans;
}

void resolve_noise_offsets(const std::map<long, double>& noise_duration_s, std::vector<RecordingPlan>* plans) {
  for (RecordingPlan& plan : *plans) {
    for (PlannedNoise& noise : plan.noises) {
      if (!noise.loop) continue;
      auto it = noise_duration_s.find(noise.noise);
      if (it == noise_duration_s.end()) throw Error("internal: no duration for noise " + std::to_string(noise.noise));
      // Rounding down keeps the offset strictly inside the noise.
      noise.offset_s = std::floor(noise.offset_fraction * it->second * 1e6) / 1e6;
    }
  }
}

namespace {

// How a command reads an rxfilename: a pipe feeds it through stdin ("<pipe> " before the command,
// argument "-"); a plain file is its argument, shell-quoted ("./" before a leading '-', so it is
// never mistaken for an option).
struct ShellInput {
  std::string before, argument;
};
ShellInput shell_input(const std::string& rxfilename) {
  if (is_pipe_rxfilename(rxfilename)) return {trim(rxfilename) + " ", "-"};
  std::string file = trim(rxfilename);
  if (starts_with(file, "-")) file = "./" + file;
  return {"", shell_quote(file)};
}

}  // namespace

std::string noise_signal_rx(const PlannedNoise& noise, const AugmentSources& sources, const std::string& program,
                            const NoiseChannels& channels) {
  const NoiseChoice& choice = sources.noises.at(static_cast<size_t>(noise.noise));
  const bool one_channel = channels.channel >= 0;
  if (!noise.needs_nested_reverberation() && !one_channel) return choice.rxfilename;
  const auto [before, input] = shell_input(choice.rxfilename);
  // One channel of a noise added as it is: SoX, as Kaldi's program without an RIR or --duration
  // drops the last sample (its output has input + RIR - 1 samples). --no-glob: a file name is not a pattern.
  if (!noise.needs_nested_reverberation()) {
    return before + "sox -D -t wav " + (before.empty() ? "--no-glob " : "") + input + " -t wav - remix " +
           std::to_string(channels.channel + 1) + " |";
  }
  std::string command = shell_quote(program);
  if (noise.rir >= 0)
    command += " " + shell_quote("--impulse-response=" + sources.rirs.at(static_cast<size_t>(noise.rir)).rxfilename);
  if (noise.extend_to_s > 0) command += " --duration=" + pipe_number(noise.extend_to_s);
  if (one_channel) command += (noise.rir >= 0 ? " --rir-channel=" : " --input-wave-channel=") + std::to_string(channels.channel);
  if (channels.every && noise.rir >= 0) command += " --multi-channel-output=true";
  if (!channels.every || noise.rir >= 0) return before + command + " " + input + " - |";
  if (channels.count < 1) throw Error("internal: the channel count of noise '" + choice.id + "' is not known");
  std::string merged = "sox -D -M";
  for (int k = 0; k < channels.count; ++k)
    merged += " -t wav --no-glob " + shell_quote("|" + before + command + " --input-wave-channel=" + std::to_string(k) + " " +
                                       input + " -");
  return merged + " -t wav - |";
}

namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + items[i];
  return out;
}

// What a pipe for Kaldi's program needs of a noise's channels (none for one microphone; ours
// takes the noise whole and chooses with --noise-channel).
NoiseChannels kaldi_noise_channels(const RecordingPlan& plan, const PlannedNoise& noise, const PipeOptions& options) {
  NoiseChannels channels;
  if (options.tsrir_extensions) return channels;
  if (plan.rir_channel >= 0) {
    channels.channel = plan.rir_channel;
  } else if (options.multi_channel_output && plan.rir >= 0) {
    channels.every = true;
    auto it = options.noise_channels.find(noise.noise);
    if (it != options.noise_channels.end()) channels.count = it->second;
  }
  return channels;
}

}  // namespace

std::string format_pipe(const RecordingPlan& plan, const AugmentSources& sources, const PipeOptions& options) {
  if (!plan.modified()) return plan.source_rx;
  // A plain file is read by the program itself (Kaldi writes "cat <file> |" first: one process
  // more per utterance); a pipe feeds it through stdin.
  const auto [before, input] = shell_input(plan.source_rx);
  std::string out = before + shell_quote(options.program);
  out += " " + std::string(options.reverb.shift_output ? "--shift-output=true" : "--shift-output=false");
  if (!options.reverb.normalize_output) out += " --normalize-output=false";
  // Kaldi's binary gives no channel at all with --multi-channel-output and no RIR: a recording
  // whose speech is not reverberated stays one channel, as ours makes it (kaldi_noise_channels).
  if (options.multi_channel_output && (plan.rir >= 0 || options.tsrir_extensions)) out += " --multi-channel-output=true";
  if (plan.rir_channel >= 0) out += " --rir-channel=" + std::to_string(plan.rir_channel);
  // A split entry takes the same channel of its noises (wav_reverberate.h's array rules).
  // (Kaldi's program is given each noise's channel alone: noise_signal_rx.)
  if (plan.rir_channel >= 0 && !plan.noises.empty() && options.tsrir_extensions)
    out += " --noise-channel=" + std::to_string(plan.rir_channel);
  if (options.sample_rate_hz > 0) out += " --sample-rate=" + format_double(options.sample_rate_hz);
  if (plan.rir >= 0)
    out += " " + shell_quote("--impulse-response=" + sources.rirs[static_cast<size_t>(plan.rir)].rxfilename);
  if (!plan.noises.empty()) {
    std::vector<std::string> signals, starts, snrs, offsets, loops, nested_rirs, nested_durations;
    bool any_loop = false, any_nested = false;
    for (const PlannedNoise& noise : plan.noises) {
      // Our program does the nested step in its own process (one process per noise less).
      const bool in_process = options.tsrir_extensions && noise.needs_nested_reverberation();
      any_nested |= in_process;
      nested_rirs.push_back(in_process && noise.rir >= 0 ? sources.rirs[static_cast<size_t>(noise.rir)].rxfilename : "");
      nested_durations.push_back(in_process ? pipe_number(noise.extend_to_s) : "0");
      if (nested_rirs.back().find(',') != std::string::npos)
        throw Error(sources.rirs[static_cast<size_t>(noise.rir)].where + ": RIR rxfilename '" + nested_rirs.back() +
                    "' contains a comma, which wav-reverberate's lists cannot hold; use --write-wavs");
      const std::string rx = in_process ? sources.noises[static_cast<size_t>(noise.noise)].rxfilename
                                        : noise_signal_rx(noise, sources, options.program, kaldi_noise_channels(plan, noise, options));
      if (rx.find(',') != std::string::npos) {
        const NoiseChoice& choice = sources.noises[static_cast<size_t>(noise.noise)];
        throw Error(choice.where + ": noise '" + choice.id + "' gives the signal '" + rx +
                    "', which contains a comma, which wav-reverberate's --additive-signals cannot hold; use --write-wavs");
      }
      signals.push_back(rx);
      starts.push_back(pipe_number(noise.start_time_s));
      snrs.push_back(pipe_number(noise.snr_db));
      offsets.push_back(pipe_number(noise.offset_s));
      loops.push_back(noise.loop ? "true" : "false");
      any_loop |= noise.loop;
    }
    out += " " + shell_quote("--additive-signals=" + joined(signals));
    out += " " + shell_quote("--start-times=" + joined(starts));
    out += " " + shell_quote("--snrs=" + joined(snrs));
    if (any_nested) {
      bool any_rir = false;
      for (const std::string& r : nested_rirs) any_rir |= !r.empty();
      if (any_rir) out += " " + shell_quote("--additive-impulse-responses=" + joined(nested_rirs));
      out += " " + shell_quote("--additive-durations=" + joined(nested_durations));
    }
    if (any_loop) {
      if (!options.tsrir_extensions)
        throw Error("--noise-start=random needs tsrir's wav-reverberate (--additive-offsets, --additive-loops); "
                    "the pipe program " + options.program + " is taken to be Kaldi's");
      out += " " + shell_quote("--additive-offsets=" + joined(offsets));
      out += " " + shell_quote("--additive-loops=" + joined(loops));
    }
    if (options.reverb.snr_reference != SnrReference::kEarlyReverb) {
      if (!options.tsrir_extensions)
        throw Error("--snr-reference=full needs tsrir's wav-reverberate; the pipe program " + options.program +
                    " is taken to be Kaldi's");
      out += " --snr-reference=" + snr_reference_name(options.reverb.snr_reference);
    }
  }
  out += " " + input + " - |";
  return out;
}

}  // namespace tsrir
