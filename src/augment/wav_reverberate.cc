#include "augment/wav_reverberate.h"

#include <algorithm>
#include <memory>

#include "augment/noise_signal.h"
#include "augment/rate_policy.h"
#include "augment/reverb_steps.h"
#include "augment/reverberate_stream.h"
#include "augment/temp_file.h"
#include "augment/wav_sink.h"
#include "io/audio_io.h"
#include "io/rxfile.h"
#include "util/log.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

std::vector<double> parse_number_list(const std::string& text, const std::string& option) {
  std::vector<double> values;
  for (const std::string& field : split_comma_list(text))
    values.push_back(parse_double(trim(field), "--" + option));
  return values;
}

const std::vector<float>& channel_of(const std::vector<std::vector<float>>& channels, int index,
                                     const std::string& what) {
  if (index < 0 || static_cast<size_t>(index) >= channels.size())
    throw Error(what + ": channel " + std::to_string(index) + " requested but it has " +
                std::to_string(channels.size()) + " channel(s)");
  return channels[static_cast<size_t>(index)];
}

// 16-bit WAV to a file (atomically), stdout or a pipe: the one writer of the streaming path too,
// fed in interleaved blocks.
void write_output(const std::string& wx, const std::vector<std::vector<float>>& channels,
                  double sample_rate_hz, long long* clipped) {
  const size_t frames = channels.empty() ? 0 : channels[0].size();
  const size_t num_channels = channels.size();
  WavSink sink(wx, static_cast<int>(num_channels), frames, sample_rate_hz, SampleFormat::kInt16);
  constexpr size_t kBlockFrames = 16384;
  if (num_channels == 1) {  // already "interleaved"
    for (size_t start = 0; start < frames; start += kBlockFrames)
      sink.write(channels[0].data() + start, std::min(kBlockFrames, frames - start));
    sink.commit();
    *clipped = sink.clipped_samples();
    return;
  }
  std::vector<float> block;
  for (size_t start = 0; start < frames; start += kBlockFrames) {
    const size_t n = std::min(kBlockFrames, frames - start);
    block.resize(n * num_channels);
    for (size_t i = 0; i < n; ++i)
      for (size_t c = 0; c < num_channels; ++c) block[i * num_channels + c] = channels[c][start + i];
    sink.write(block.data(), n);
  }
  sink.commit();
  *clipped = sink.clipped_samples();
}

}  // namespace

void WavReverberateOptions::Register(OptionsItf* opts) {
  opts->Register("multi-channel-output", &multi_channel_output,
                 "One output channel per RIR channel; channel c of every additive signal goes to output channel c at "
                 "its SNR against that channel's speech (additive signals must have as many channels; a noise "
                 "reverberated by --additive-impulse-responses gets one per channel of its RIR)");
  opts->Register("input-wave-channel", &input_wave_channel, "Channel of the input used to make the output");
  opts->Register("rir-channel", &rir_channel, "Channel of the RIR, used when --multi-channel-output=false");
  opts->Register("noise-channel", &noise_channel,
                 "Channel of the additive signals, used when --multi-channel-output=false");
  opts->Register("impulse-response", &impulse_response,
                 "rxfilename of the room impulse response (file, 'command |' or -); empty = no reverberation");
  opts->Register("additive-signals", &additive_signals, "Comma-separated list of additive signals (rxfilenames)");
  opts->Register("snrs", &snrs, "Comma-separated SNRs in dB, one per additive signal");
  opts->Register("start-times", &start_times,
                 "Comma-separated start times in seconds, one per additive signal, into the reverberant input; "
                 "a start beyond its end adds nothing");
  reverb.Register(opts);
  opts->Register("volume", &reverb.volume, "If > 0, a gain applied instead of --normalize-output");
  opts->Register("duration", &reverb.duration_s,
                 "If > 0, output duration in seconds: trimmed if shorter, tiled (repeated) if longer");
  opts->Register("additive-offsets", &additive_offsets,
                 "tsrir extension: comma-separated positions (s) in each additive signal where reading starts "
                 "(rounded to the nearest sample); empty = 0 for all");
  opts->Register("loop-additive-signals", &reverb.loop_additive_signals,
                 "tsrir extension: tile each additive signal from its offset to the end of the reverberant signal; "
                 "its power for the SNR is then measured over exactly the samples added");
  opts->Register("additive-loops", &additive_loops,
                 "tsrir extension: comma-separated true/false, one per additive signal: loop that signal as "
                 "--loop-additive-signals does for all");
  opts->Register("additive-impulse-responses", &additive_impulse_responses,
                 "tsrir extension: comma-separated RIR rxfilenames, one field per additive signal (empty = none): "
                 "that signal is first reverberated as Kaldi's nested `wav-reverberate --impulse-response=<rir> "
                 "<signal> -` would, in this process");
  opts->Register("additive-durations", &additive_durations,
                 "tsrir extension: comma-separated durations (s), one per additive signal (0 = as is): that signal "
                 "is first repeated or cut to it as Kaldi's nested `wav-reverberate --duration=<s>` would");
  opts->Register("kaldi-compat", &reverb.kaldi_compat,
                 "tsrir extension: reproduce the output of Kaldi's wav-reverberate sample for sample (up to float "
                 "rounding), its defects included: the error of its FFT block convolution (its DC and Nyquist "
                 "bins are multiplied as one complex number), 16-bit output truncated instead of rounded, and with "
                 "--shift-output=false the reverberant tail replaced by the first samples; the input is then "
                 "always held in memory, as Kaldi does");
  opts->Register("sample-rate", &sample_rate_hz,
                 "tsrir extension: if > 0, the output's rate in Hz: an input at another rate is resampled to it "
                 "(libsox rate -v; RIRs and additive signals are always resampled to the output's rate)");
  opts->Register("max-in-memory-duration", &max_in_memory_s,
                 "tsrir extension: inputs longer than this many seconds are reverberated in passes over the file "
                 "with memory independent of their length (same output; a piped input is first copied to a "
                 "temporary file, as is the unscaled output: next to a file output, else in $TMPDIR); 0 = always");
}

std::vector<std::vector<float>> read_channels_at_rate(const std::string& rx, double sample_rate_hz,
                                                      const std::string& context) {
  AudioInfo info;
  std::vector<std::vector<float>> channels = read_audio_channels(rx, &info, context);
  if (info.sample_rate_hz != sample_rate_hz)
    for (auto& channel : channels) channel = resample(channel, info.sample_rate_hz, sample_rate_hz);
  return channels;
}

std::vector<std::string> split_comma_list(const std::string& text) {
  std::vector<std::string> out;
  for (const std::string& field : split(text, ','))
    if (!field.empty()) out.push_back(field);
  return out;
}

namespace {

// What reverberates each output channel: its RIR (absent without one) and additive signals.
struct OutputChannelSetup {
  std::unique_ptr<PreparedRir> rir;
  std::vector<AdditiveSignal> additive;
};

// Kaldi's channel rules (--multi-channel-output, --rir-channel, --noise-channel), shared by the
// in-memory and the streaming path. The additive channels used are moved into the setups (each
// output channel takes its own channel of each signal).
std::vector<OutputChannelSetup> setup_output_channels(
    double sample_rate_hz, const std::vector<std::vector<float>>& rir_channels,
    std::vector<std::vector<std::vector<float>>> additive_channels, const std::vector<double>& snrs_db,
    const std::vector<double>& start_times_s, const std::vector<double>& offsets_s,
    const WavReverberateOptions& config) {
  const bool have_rir = !rir_channels.empty();
  const size_t num_out = (config.multi_channel_output && have_rir) ? rir_channels.size() : 1;
  if (config.multi_channel_output && config.rir_channel != 0)
    log_warning("--rir-channel is ignored as --multi-channel-output is true");
  if (have_rir && !config.multi_channel_output && !config.rir_channel_given)
    warn_channel_used(static_cast<int>(rir_channels.size()), config.rir_channel, "--impulse-response",
                      "--rir-channel chooses");
  if (!(config.multi_channel_output && have_rir) && !config.noise_channel_given)
    for (size_t i = 0; i < additive_channels.size(); ++i)
      warn_channel_used(static_cast<int>(additive_channels[i].size()), config.noise_channel,
                        "additive signal " + std::to_string(i + 1), "--noise-channel chooses");
  for (size_t i = 0; i < additive_channels.size(); ++i) {
    if (config.multi_channel_output && have_rir && additive_channels[i].size() != num_out)
      throw Error("additive signal " + std::to_string(i + 1) + " has " + std::to_string(additive_channels[i].size()) +
                  " channels but the impulse response has " + std::to_string(num_out) +
                  " (--multi-channel-output=true needs them equal)");
  }
  std::vector<bool> loops;
  for (const std::string& word : split_comma_list(config.additive_loops)) {
    if (word != "true" && word != "false")
      throw Error("--additive-loops: expected true or false, got '" + word + "'");
    loops.push_back(word == "true");
  }
  if (!loops.empty() && loops.size() != additive_channels.size())
    throw Error("--additive-loops has " + std::to_string(loops.size()) + " entries but --additive-signals has " +
                std::to_string(additive_channels.size()));
  std::vector<OutputChannelSetup> setups(num_out);
  for (size_t c = 0; c < num_out; ++c) {
    if (have_rir) {
      const int rir_index = config.multi_channel_output ? static_cast<int>(c) : config.rir_channel;
      setups[c].rir =
          std::make_unique<PreparedRir>(channel_of(rir_channels, rir_index, "impulse response"), sample_rate_hz);
    }
    std::vector<AdditiveSignal>& additive = setups[c].additive;
    additive.resize(additive_channels.size());
    for (size_t i = 0; i < additive_channels.size(); ++i) {
      const int noise_index = (config.multi_channel_output && have_rir) ? static_cast<int>(c) : config.noise_channel;
      channel_of(additive_channels[i], noise_index, "additive signal " + std::to_string(i + 1));  // checks
      additive[i].samples = std::make_shared<const std::vector<float>>(
          std::move(additive_channels[i][static_cast<size_t>(noise_index)]));
      additive[i].snr_db = snrs_db.at(i);
      additive[i].start_time_s = start_times_s.at(i);
      additive[i].offset_s = offsets_s.empty() ? 0.0 : offsets_s.at(i);
      additive[i].loop = !loops.empty() && loops[i];
    }
  }
  return setups;
}

std::vector<std::vector<float>> reverberate_in_memory(
    const std::vector<std::vector<float>>& input_channels, double sample_rate_hz,
    const std::vector<std::vector<float>>& rir_channels, std::vector<std::vector<std::vector<float>>> additive_channels,
    const std::vector<double>& snrs_db, const std::vector<double>& start_times_s,
    const std::vector<double>& offsets_s, const WavReverberateOptions& config) {
  const std::vector<float>& input = channel_of(input_channels, config.input_wave_channel, "input");
  const std::vector<OutputChannelSetup> setups = setup_output_channels(
      sample_rate_hz, rir_channels, std::move(additive_channels), snrs_db, start_times_s, offsets_s, config);
  std::vector<std::vector<float>> outputs(setups.size());
  for (size_t c = 0; c < setups.size(); ++c)
    outputs[c] = reverberate_channel(input, sample_rate_hz, setups[c].rir.get(), setups[c].additive, config.reverb);
  return outputs;
}

}  // namespace

std::vector<std::vector<float>> wav_reverberate_channels(
    const std::vector<std::vector<float>>& input_channels, double sample_rate_hz,
    const std::vector<std::vector<float>>& rir_channels,
    const std::vector<std::vector<std::vector<float>>>& additive_channels,
    const std::vector<double>& snrs_db, const std::vector<double>& start_times_s,
    const std::vector<double>& offsets_s, const WavReverberateOptions& config) {
  return reverberate_in_memory(input_channels, sample_rate_hz, rir_channels, additive_channels, snrs_db,
                               start_times_s, offsets_s, config);
}

namespace {
// --additive-signals, --snrs, --start-times and --additive-offsets agree entry by entry.
void check_additive_lists(const WavReverberateOptions& config, const std::vector<std::string>& additive_rx,
                          const std::vector<double>& snrs, const std::vector<double>& start_times,
                          const std::vector<double>& offsets) {
  if (!additive_rx.empty()) {
    if (config.snrs.empty() || config.start_times.empty())
      throw Error("--additive-signals requires --snrs and --start-times");
    if (snrs.size() != additive_rx.size() || start_times.size() != additive_rx.size())
      throw Error("--additive-signals has " + std::to_string(additive_rx.size()) + " entries but --snrs has " +
                  std::to_string(snrs.size()) + " and --start-times " + std::to_string(start_times.size()));
    if (!offsets.empty() && offsets.size() != additive_rx.size())
      throw Error("--additive-offsets has " + std::to_string(offsets.size()) + " entries but --additive-signals has " +
                  std::to_string(additive_rx.size()));
  } else if (!offsets.empty()) {
    throw Error("--additive-offsets given without --additive-signals");
  }
}

// Which channels of an additive signal the output uses (Kaldi's rule, setup_output_channels):
// every one with --multi-channel-output and an RIR, else --noise-channel's.
std::vector<bool> used_noise_channels(const WavReverberateOptions& config, size_t channels, size_t rir_channels) {
  std::vector<bool> used(channels, false);
  if (config.multi_channel_output && rir_channels > 0) used.assign(channels, true);
  else if (config.noise_channel >= 0 && static_cast<size_t>(config.noise_channel) < channels)
    used[static_cast<size_t>(config.noise_channel)] = true;
  return used;
}

// One additive signal through the nested-noise extension (Kaldi's nested `wav-reverberate
// [--impulse-response=<rir>] [--duration=<s>] <noise> -`, then resampled to `fs`). Channels as
// a microphone array needs them (issue 33): with an RIR, channel k = the noise's channel 0 (the
// source's signal, as the nested program's --input-wave-channel=0) through the RIR's channel k,
// what Kaldi's nested `wav-reverberate --multi-channel-output=true --impulse-response=<rir>` makes;
// without one, each channel of the noise extended (Kaldi's nested program would keep channel 0
// only). Only the channels the output uses are computed; the others are left empty.
std::vector<std::vector<float>> nested_additive_signal(const WavReverberateOptions& config, const std::string& noise_rx,
                                                       const std::string& rir_rx, double duration_s, double fs,
                                                       size_t speech_rir_channels) {
  AudioInfo info;
  size_t needed = static_cast<size_t>(-1);
  if (rir_rx.empty()) {
    // Only the first int(fs * duration) samples matter then (noise_signal.h): a 30 s noise file
    // cut to a 10 s utterance is read that far. An unreadable file is left to the read below,
    // which reports it.
    const std::string t = trim(noise_rx);
    try {
      if (t != "-" && !is_pipe_rxfilename(t))
        needed = kaldi_duration_samples(probe_audio(t).sample_rate_hz, static_cast<float>(duration_s));
    } catch (const Error&) {
    }
  }
  std::vector<std::vector<float>> noise = read_audio_channels_prefix(noise_rx, needed, &info, "--additive-signals");
  std::vector<std::vector<float>> rir;
  if (!rir_rx.empty()) rir = read_channels_at_rate(rir_rx, info.sample_rate_hz, "--additive-impulse-responses");
  const size_t channels = rir.empty() ? noise.size() : rir.size();
  const std::vector<bool> used = used_noise_channels(config, channels, speech_rir_channels);
  std::vector<std::vector<float>> out(channels);
  for (size_t k = 0; k < channels; ++k) {
    if (!used[k]) continue;
    if (rir.empty()) {
      out[k] = nested_noise_signal(std::move(noise[k]), info.sample_rate_hz, nullptr, duration_s, info.int16_samples,
                                   config.reverb.kaldi_compat);
    } else {
      // Each microphone hears channel 0 (the source's signal) through its own RIR channel: channel
      // 0 is lent to each, not copied per microphone.
      const PreparedRir prepared(std::move(rir[k]), info.sample_rate_hz);
      out[k] = nested_noise_signal(noise.at(0), info.sample_rate_hz, &prepared, duration_s, info.int16_samples,
                                   config.reverb.kaldi_compat);
    }
    if (info.sample_rate_hz != fs) out[k] = resample(out[k], info.sample_rate_hz, fs);
  }
  return out;
}

// Every additive signal's channels at `fs`: read as they are, or made by the nested-noise
// extensions (--additive-impulse-responses, --additive-durations: fields by position, an empty
// field or none given = the plain signal).
std::vector<std::vector<std::vector<float>>> load_additive_signals(const WavReverberateOptions& config,
                                                                   const std::vector<std::string>& additive_rx,
                                                                   double fs, size_t speech_rir_channels) {
  const std::vector<std::string> nested_rirs = split(config.additive_impulse_responses, ',');
  const std::vector<std::string> nested_durations = split(config.additive_durations, ',');
  if (!config.additive_impulse_responses.empty() && nested_rirs.size() != additive_rx.size())
    throw Error("--additive-impulse-responses has " + std::to_string(nested_rirs.size()) +
                " fields but --additive-signals has " + std::to_string(additive_rx.size()));
  if (!config.additive_durations.empty() && nested_durations.size() != additive_rx.size())
    throw Error("--additive-durations has " + std::to_string(nested_durations.size()) +
                " fields but --additive-signals has " + std::to_string(additive_rx.size()));
  std::vector<std::vector<std::vector<float>>> additive;
  for (size_t i = 0; i < additive_rx.size(); ++i) {
    const std::string rir_rx = config.additive_impulse_responses.empty() ? "" : trim(nested_rirs[i]);
    const double duration = !config.additive_durations.empty() && !trim(nested_durations[i]).empty()
                                ? parse_double(trim(nested_durations[i]), "--additive-durations")
                                : 0.0;
    if (rir_rx.empty() && duration <= 0)
      additive.push_back(read_channels_at_rate(additive_rx[i], fs, "--additive-signals"));
    else
      additive.push_back(nested_additive_signal(config, additive_rx[i], rir_rx, duration, fs, speech_rir_channels));
  }
  return additive;
}
}  // namespace

long long run_wav_reverberate(const WavReverberateOptions& config, const std::string& input_rx,
                              const std::string& output_wx) {
  const std::vector<std::string> additive_rx = split_comma_list(config.additive_signals);
  const std::vector<double> snrs = parse_number_list(config.snrs, "snrs");
  const std::vector<double> start_times = parse_number_list(config.start_times, "start-times");
  const std::vector<double> offsets = parse_number_list(config.additive_offsets, "additive-offsets");
  check_additive_lists(config, additive_rx, snrs, start_times, offsets);

  // Kaldi's numerics are those of its whole-signal computation: no passes over the file.
  const double max_in_memory_s = config.reverb.kaldi_compat ? 1e300 : config.max_in_memory_s;
  SpeechInput input =
      open_speech_input(input_rx, max_in_memory_s, temp_base_for_output(output_wx, "input"), "input");
  const AudioInfo input_info = input.on_disk() ? probe_audio(input.path) : input.info;
  if (!config.input_channel_given)
    warn_channel_used(input_info.channels, config.input_wave_channel, "input", "--input-wave-channel chooses");
  const double fs = config.sample_rate_hz > 0 ? config.sample_rate_hz : input_info.sample_rate_hz;
  if (fs != input_info.sample_rate_hz) {
    if (input.on_disk())
      throw Error("input: at " + format_double(input_info.sample_rate_hz) + " Hz, longer than --max-in-memory-duration: " +
                  "cannot be resampled to --sample-rate=" + format_double(fs) + " (resample it first)");
    for (auto& channel : input.channels) channel = resample(channel, input_info.sample_rate_hz, fs);
  }

  // Kaldi never checks the RIR's rate; applying a 48 kHz RIR to 16 kHz speech sample by sample
  // would stretch the room 3x, so RIRs (like additive signals) are resampled to the speech's rate.
  std::vector<std::vector<float>> rir;
  if (!config.impulse_response.empty())
    rir = read_channels_at_rate(config.impulse_response, fs, "--impulse-response");
  std::vector<std::vector<std::vector<float>>> additive =
      load_additive_signals(config, additive_rx, fs, rir.size());
  long long clipped = 0;
  size_t total = 0;
  if (!input.on_disk()) {
    std::vector<std::vector<float>> output =
        reverberate_in_memory(input.channels, fs, rir, std::move(additive), snrs, start_times, offsets, config);
    input.channels.clear();
    // Kaldi truncates toward zero (the writer would round): done first, the writer then keeps it.
    long long truncated_clipped = 0;
    if (config.reverb.kaldi_compat)
      for (auto& channel : output) truncated_clipped += kaldi_truncate_to_int16(&channel);
    write_output(output_wx, output, fs, &clipped);
    clipped += truncated_clipped;
    total = output.size() * output[0].size();
  } else {
    const std::vector<OutputChannelSetup> setups =
        setup_output_channels(fs, rir, std::move(additive), snrs, start_times, offsets, config);
    std::vector<StreamChannel> channels(setups.size());
    for (size_t c = 0; c < setups.size(); ++c) {
      channels[c].rir = setups[c].rir.get();
      channels[c].additive = setups[c].additive;
    }
    log_info(trim(input_rx) + ": longer than " + format_double(config.max_in_memory_s) +
             " s: reverberated in passes over the file (memory independent of its length)");
    StreamSettings settings;
    settings.temp_base = temp_base_for_output(output_wx, "spill");
    const StreamResult result = reverberate_stream(input.path, "input", input.rx, config.input_wave_channel, channels,
                                                   config.reverb, output_wx, settings);
    clipped = result.clipped_samples;
    total = result.frames * static_cast<size_t>(result.channels);
  }
  if (clipped > 0) {
    log_warning("clipped " + std::to_string(clipped) + " samples out of total " + std::to_string(total) +
                ". Reduce volume?");
  }
  return clipped;
}

}  // namespace tsrir
