// wav-reverberate: drop-in for Kaldi's featbin/wav-reverberate (same name, options and syntax).
#include "augment/kaldi_options.h"
#include "augment/wav_reverberate.h"
#include "util/heap_pages.h"

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
    "Exit status: 0 on success, 1 for any error (Kaldi's binary exits 255; its scripts only test for\n"
    "non-zero).\n"
    "\n"
    "Semantics (Kaldi's): the SNR of each additive signal is relative to the energy of the speech\n"
    "convolved with the early part of the RIR (1 ms before to 50 ms after its largest sample); each\n"
    "signal is added at int(start-time * fs) into the unshifted reverberant signal, truncated to it;\n"
    "the output is rescaled to the input's power (--normalize-output) or by --volume; its length is\n"
    "the input's (--shift-output=true: advanced by the RIR's peak index), or int(fs * --duration)\n"
    "with the signal tiled when longer.\n"
    "Differences from Kaldi: inputs may be 16/24/32-bit PCM or float WAV (or FLAC...) at any rate;\n"
    "the RIR and additive signals are resampled to the input's rate; the convolution is exact (Kaldi's\n"
    "FFT block convolution multiplies its DC and Nyquist bins as one complex number: each block gets\n"
    "a spurious constant + alternating error, a few LSB on speech, thousands on a one-tap RIR); with\n"
    "--shift-output=false the output is the full convolution including the reverberant tail (Kaldi\n"
    "replaces the tail by the signal's first samples); 16-bit output is rounded to nearest (Kaldi\n"
    "truncates); --help prints to stdout. --kaldi-compat=true reproduces Kaldi's output instead\n"
    "(within 2 LSB of its binary on the parity test's pipes), defects included.\n"
    "Extensions (tsrir; Kaldi's binary rejects them): --additive-offsets, --loop-additive-signals, --additive-loops,\n"
    "--additive-impulse-responses, --additive-durations (Kaldi's nested noise commands in one process),\n"
    "--snr-reference, --kaldi-compat, --max-in-memory-duration.\n"
    "Long inputs: beyond --max-in-memory-duration (default 300 s) the input is read in three passes\n"
    "(statistics; reverberation to a temporary file; scaling and encoding), so a 2-hour utterance\n"
    "needs ~30 MB instead of ~1.3 GB, with the same output; the temporary holds the output as float\n"
    "(~230 MB per hour at 16 kHz) next to a file output, else in $TMPDIR (default /tmp).\n";

}  // namespace

int main(int argc, char** argv) {
  // One process per utterance in Kaldi's pipes: page faults are a large part of its cost.
  tsrir::use_huge_pages_for_heap(64u << 20);
  tsrir::WavReverberateOptions options;
  const tsrir::KaldiOptionParser* parser = nullptr;
  return tsrir::run_kaldi_program(
      "wav-reverberate", kUsage, argc, argv, 2,
      [&](tsrir::KaldiOptionParser& po) {
        options.Register(&po);
        parser = &po;
      },
      [&](const std::vector<std::string>& args) {
        // A multichannel input whose channel was not chosen gets a warning naming the one used.
        options.input_channel_given = parser->given("input-wave-channel");
        options.rir_channel_given = parser->given("rir-channel");
        options.noise_channel_given = parser->given("noise-channel");
        tsrir::run_wav_reverberate(options, args[0], args[1]);
        return 0;
      });
}
