// wav-reverberate: drop-in for Kaldi's featbin/wav-reverberate (same name, options and syntax).
#include <iostream>

#include "augment/kaldi_options.h"
#include "augment/wav_reverberate.h"
#include "util/cli.h"

namespace {

const char* kUsage =
    "Corrupts the wave file supplied via input pipe with the specified room impulse response and\n"
    "additive noise signals: tsrir's drop-in replacement for Kaldi's wav-reverberate.\n"
    "Usage:  wav-reverberate [options...] <wav-in-rxfilename> <wav-out-wxfilename>\n"
    "e.g.\n"
    "  wav-reverberate --impulse-response=rir.wav --additive-signals='noise1.wav,noise2.wav' \\\n"
    "    --snrs='10,5' --start-times='0,3.21' input.wav output.wav\n"
    "  cat speech.wav | wav-reverberate --shift-output=true --impulse-response='sox r.flac -t wav - |' - - | ...\n"
    "\n"
    "Why this name: Kaldi's steps/data/reverberate_data_dir.py and augment_data_dir.py call\n"
    "`wav-reverberate` through PATH; put tsrir's bin directory first on PATH (e.g. in path.sh) and\n"
    "those scripts use this program unchanged. reverberate-data writes pipes that call this program\n"
    "by its absolute path, so they never pick up Kaldi's binary by accident.\n"
    "\n"
    "Command-line syntax is Kaldi's own (not the other tsrir programs'): options come before the\n"
    "two positional arguments and only in the form --name=value (a bare --name means true for a\n"
    "boolean; `--name value` is an error), names are case-insensitive and '_' equals '-'.\n"
    "Exit status: 0 on success, 1 for a wrong number of arguments, 255 for any other error.\n"
    "\n"
    "Semantics (Kaldi's): the SNR of each additive signal is relative to the energy of the speech\n"
    "convolved with the early part of the RIR (1 ms before to 50 ms after its largest sample); each\n"
    "signal is added at int(start-time * fs) into the unshifted reverberant signal, truncated to it;\n"
    "the output is rescaled to the input's power (--normalize-output) or by --volume; its length is\n"
    "the input's (--shift-output=true: advanced by the RIR's peak index), or int(fs * --duration)\n"
    "with the signal tiled when longer.\n"
    "Differences from Kaldi: inputs may be 16/24/32-bit PCM or float WAV (or FLAC...) at any rate;\n"
    "the RIR and additive signals are resampled to the input's rate; with --shift-output=false the\n"
    "output is the full convolution including the reverberant tail (Kaldi replaces the tail by the\n"
    "signal's first samples); 16-bit output is rounded to nearest (Kaldi truncates), a <= 1 LSB\n"
    "difference; --help prints to stdout.\n"
    "Extensions (tsrir; Kaldi's binary rejects them): --additive-offsets, --loop-additive-signals, --additive-loops,\n"
    "--additive-impulse-responses, --additive-durations (Kaldi's nested noise commands in one process),\n"
    "--snr-reference, --max-in-memory-duration.\n"
    "Long inputs: beyond --max-in-memory-duration (default 300 s) the input is read in three passes\n"
    "(statistics; reverberation to a temporary file; scaling and encoding), so a 2-hour utterance\n"
    "needs ~30 MB instead of ~1.3 GB, with the same output; the temporary holds the output as float\n"
    "(~230 MB per hour at 16 kHz) next to a file output, else in $TMPDIR (default /tmp).\n";

}  // namespace

int main(int argc, char** argv) {
  tsrir::WavReverberateConfig config;
  float volume = 0.0f, duration = 0.0f;
  std::string snr_reference = "early";
  auto define = [&](tsrir::KaldiOptionParser& po) {
    po.add("multi-channel-output", &config.multi_channel_output,
           "One output channel per RIR channel (additive signals must have as many channels)");
    po.add("input-wave-channel", &config.input_wave_channel, "Channel of the input used to make the output");
    po.add("rir-channel", &config.rir_channel, "Channel of the RIR, used when --multi-channel-output=false");
    po.add("noise-channel", &config.noise_channel,
           "Channel of the additive signals, used when --multi-channel-output=false");
    po.add("impulse-response", &config.impulse_response,
           "rxfilename of the room impulse response (file, 'command |' or -); empty = no reverberation");
    po.add("additive-signals", &config.additive_signals, "Comma-separated list of additive signals (rxfilenames)");
    po.add("snrs", &config.snrs, "Comma-separated SNRs in dB, one per additive signal");
    po.add("start-times", &config.start_times,
           "Comma-separated start times in seconds, one per additive signal, into the reverberant input; "
           "a start beyond its end adds nothing");
    po.add("normalize-output", &config.reverb.normalize_output,
           "Scale the output to the power of the input after reverberation and noise");
    po.add("shift-output", &config.reverb.shift_output,
           "Advance the output by the RIR's peak index (direct-path delay) and keep the input's length");
    po.add("volume", &volume, "If > 0, a gain applied instead of --normalize-output");
    po.add("duration", &duration,
           "If > 0, output duration in seconds: trimmed if shorter, tiled (repeated) if longer");
    po.add("additive-offsets", &config.additive_offsets,
           "tsrir extension: comma-separated positions (s) in each additive signal where reading starts "
           "(rounded to the nearest sample); empty = 0 for all");
    po.add("loop-additive-signals", &config.reverb.loop_additive_signals,
           "tsrir extension: tile each additive signal from its offset to the end of the reverberant signal; "
           "its power for the SNR is then measured over exactly the samples added");
    po.add("additive-loops", &config.additive_loops,
           "tsrir extension: comma-separated true/false, one per additive signal: loop that signal as "
           "--loop-additive-signals does for all");
    po.add("additive-impulse-responses", &config.additive_impulse_responses,
           "tsrir extension: comma-separated RIR rxfilenames, one field per additive signal (empty = none): "
           "that signal is first reverberated as Kaldi's nested `wav-reverberate --impulse-response=<rir> "
           "<signal> -` would, in this process");
    po.add("additive-durations", &config.additive_durations,
           "tsrir extension: comma-separated durations (s), one per additive signal (0 = as is): that signal "
           "is first repeated or cut to it as Kaldi's nested `wav-reverberate --duration=<s>` would");
    po.add("max-in-memory-duration", &config.max_in_memory_s,
           "tsrir extension: inputs longer than this many seconds are reverberated in passes over the file "
           "with memory independent of their length (same output; a piped input is first copied to a "
           "temporary file, as is the unscaled output: next to a file output, else in $TMPDIR); 0 = always");
    po.add("snr-reference", &snr_reference,
           "tsrir extension: early = Kaldi's early-reverberation energy, full = the whole reverberant "
           "speech x*h (mean over its N+M-1 samples)");
  };
  return tsrir::run_kaldi_program("wav-reverberate", kUsage, argc, argv, 2, define,
                                  [&](const std::vector<std::string>& args) {
                                    config.reverb.volume = volume;
                                    config.reverb.duration_s = duration;
                                    config.reverb.snr_reference = tsrir::parse_snr_reference(snr_reference);
                                    tsrir::run_wav_reverberate(config, args[0], args[1]);
                                    return 0;
                                  });
}
