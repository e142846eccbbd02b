// reverberate-data: a far-field copy of a Kaldi data directory (RIRs + looped real noise).
#include <malloc.h>

#include <string>
#include <vector>

#include "augment/reverberate_data.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/strings.h"

namespace {

const char* kUsage =
    "Makes a far-field copy of a Kaldi data directory: every recording convolved with an RIR drawn\n"
    "from the RIR lists and mixed with a noise from the noise lists, started at a random offset and\n"
    "looped to cover the speech, at an SNR drawn from --snrs (x_f = x ⊛ r + λ·n[t + l]).\n"
    "\n"
    "Usage: reverberate-data [options] <in-data-dir> <out-data-dir>\n"
    "e.g.\n"
    "  reverberate-data --rir-set-parameters '0.5, rirs/small/rir_list' \\\n"
    "    --rir-set-parameters '0.5, rirs/medium/rir_list' --noise-set-parameters noise/noise_list \\\n"
    "    --snrs 1:2 --num-replications 1 --prefix rvb --random-seed 7 data/train data/train_rvb\n"
    "  reverberate-data --rir-set-parameters rir.scp --noise-set-parameters noise.scp \\\n"
    "    --write-wavs exp/rvb_wavs --num-threads 2 data/test data/test_rvb\n"
    "\n"
    "Inputs: wav.scp and utt2spk (text, segments, utt2uniq, spk2utt, reco2file_and_channel and vad.scp\n"
    "are carried over when present). Lists are Kaldi rir_list / noise_list files or scps (<id> <rx>).\n"
    "Set weights and per-item --probability follow Kaldi's reverberate_data_dir.py, including the\n"
    "smoothing towards uniform; the draws are per recording from (seed, copy, id), so the same seed\n"
    "gives the same directory for any --num-threads (statistically, not bit-for-bit, equivalent to\n"
    "Kaldi's Python random sequence). Isotropic noises are only used with RIRs of the room they are\n"
    "linked to; point-source noises with any RIR. Every noise is added as background noise (not\n"
    "reverberated); Kaldi's foreground/background SNR options and --max-noises-per-minute do not exist.\n"
    "\n"
    "SNR (--snr-reference): early (default, Kaldi's): relative to the speech convolved with the\n"
    "RIR's direct path and early reflections (1 ms before to 50 ms after its largest sample);\n"
    "full: relative to the whole reverberant speech. The noise power is that of the samples actually\n"
    "added (offset and loop included), so the realised SNR is the requested one.\n"
    "--snrs: 'lo:hi' = uniform in [lo, hi) dB (default 1:2, the paper's benchmark); 'a,b,c' = one of\n"
    "the values; 'x' = always x.\n"
    "\n"
    "Output: <out-data-dir> with ids <prefix><copy>-<id> (Kaldi's; unchanged without a prefix), sorted\n"
    "tables, utt2uniq (new id -> original), regenerated spk2utt; checked like\n"
    "utils/validate_data_dir.sh --no-feats and written to a temporary directory renamed at the end,\n"
    "so a failure never leaves a partial directory (an existing <out-data-dir> or --write-wavs\n"
    "directory is replaced only then, as a whole). reco2dur is not carried over (as Kaldi).\n"
    "wav.scp: without --write-wavs every entry is a pipe that regenerates the recording on the fly,\n"
    "  [<source pipe> |] <dir>/wav-reverberate --shift-output=true --impulse-response=<rir>\n"
    "    --additive-signals=<noise> --start-times=0 --snrs=<snr> --additive-offsets=<s>\n"
    "    --loop-additive-signals=true <source wav or -> - |\n"
    "  (all paths shell-quoted; the random draws are written out, so each pipe is deterministic).\n"
    "  With --write-wavs=<dir>, 16-bit wavs <dir>/<new-id>.wav are written (any toolkit can read them);\n"
    "  the same seed gives the same audio in both modes. Relative RIR/noise paths are used as given,\n"
    "  as Kaldi does: pipes must run from the same directory.\n"
    "Recordings shorter than the RIR are fine; shorter noises are looped; RIRs and noises at another\n"
    "sample rate are resampled to the speech's rate, in both modes; --source-sampling-rate (Kaldi's\n"
    "option) is accepted and, with --write-wavs, checked against each recording's rate.\n"
    "Long recordings: with --write-wavs, those beyond --max-in-memory-duration (default 300 s) are\n"
    "read in passes with memory independent of their length (a 2-hour one: ~30 MB, not ~2 GB) and\n"
    "give the same wav; a piped one is first copied into the wav directory, as is the unscaled output\n"
    "(float, ~230 MB per hour at 16 kHz), both removed at once. Pipe mode streams in wav-reverberate.\n";

// Kaldi's reverberate_data_dir.py takes booleans as "--shift-output true"; accept that form too.
std::vector<std::string> join_boolean_values(int argc, char** argv, const std::vector<std::string>& flags) {
  std::vector<std::string> out{argv[0]};
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    bool is_flag = false;
    for (const auto& f : flags) is_flag |= (a == "--" + f);
    if (is_flag && i + 1 < argc) {
      std::string next = argv[i + 1];
      for (char& c : next) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (next == "true" || next == "false") {
        out.push_back(a + "=" + next);
        ++i;
        continue;
      }
    }
    out.push_back(a);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // Every utterance allocates and frees ~1 MB buffers; with glibc's defaults each one is a fresh
  // mmap whose pages fault in again (~7% of the run). Keep freed memory in the heap instead.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  return tsrir::run_program("reverberate-data", [&]() {
    tsrir::CommandLine cl("reverberate-data", kUsage);
    tsrir::ReverberateDataOptions o;
    std::string snr_reference = "early";
    long long seed = 0;
    cl.multi_option("rir-set-parameters", &o.rir_set_parameters,
                    "'[weight,] rir_list': an RIR list (Kaldi rir_list or scp) and its weight; repeatable");
    cl.multi_option("noise-set-parameters", &o.noise_set_parameters,
                    "'[weight,] noise_list': a noise list (Kaldi noise_list or scp) and its weight; repeatable");
    cl.option("num-replications", &o.num_replications, "number of reverberated copies of each recording");
    cl.option("prefix", &o.prefix, "id prefix; copies are <prefix><i>-<id> (forced to rvb for several copies)");
    cl.option("snrs", &o.snrs, "SNRs in dB: lo:hi (uniform range), a,b,c (list) or x");
    cl.option("snr-reference", &snr_reference, "early (Kaldi: direct + early reverberation) or full");
    cl.option("speech-rvb-probability", &o.speech_rvb_probability, "probability of reverberating a recording");
    cl.option("noise-addition-probability", &o.noise_addition_probability, "probability of adding noise");
    cl.option("noise-start", &o.noise_start, "random (offset uniform over the noise) or zero");
    cl.flag("shift-output", &o.shift_output, "advance the output by the RIR's direct-path delay");
    cl.flag("normalize-output", &o.normalize_output, "rescale each output to its input's power");
    cl.flag("include-original-data", &o.include_original_data, "also keep the originals as copy 0");
    cl.option("random-seed", &seed, "random seed");
    cl.option("source-sampling-rate", &o.source_sampling_rate_hz,
              "if > 0, the speech's rate in Hz (checked with --write-wavs; RIRs and noises are always resampled "
              "to the speech's rate)");
    cl.option("rir-smoothing-weight", &o.rir_smoothing_weight, "RIR probabilities mixed with uniform (Kaldi)");
    cl.option("noise-smoothing-weight", &o.noise_smoothing_weight, "noise probabilities mixed with uniform (Kaldi)");
    cl.option("write-wavs", &o.write_wavs, "write 16-bit wavs into this directory instead of pipes");
    cl.option("pipe-program", &o.pipe_program,
              "program called by the pipes (default: wav-reverberate next to this program)");
    cl.option("num-threads", &o.num_threads, "threads for --write-wavs");
    cl.option("max-in-memory-duration", &o.max_in_memory_s,
              "with --write-wavs: recordings longer than this many seconds are reverberated in passes over the "
              "file, with memory independent of their length and the same wav (temporaries in the wav dir); "
              "0 = all");
    std::vector<std::string> args =
        join_boolean_values(argc, argv, {"shift-output", "normalize-output", "include-original-data"});
    std::vector<const char*> cargs;
    for (const auto& a : args) cargs.push_back(a.c_str());
    tsrir::register_output_options(&cl);
    std::vector<std::string> dirs = cl.parse(static_cast<int>(cargs.size()), cargs.data(), 2, 2);
    o.snr_reference = tsrir::parse_snr_reference(snr_reference);
    o.random_seed = static_cast<uint64_t>(seed);
    tsrir::reverberate_data_dir(dirs[0], dirs[1], o);
    return 0;
  });
}
