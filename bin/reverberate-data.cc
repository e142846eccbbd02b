// reverberate-data: a far-field copy of a Kaldi data directory (RIRs + looped real noise).
#include <malloc.h>

#include <string>
#include <vector>

#include "augment/reverberate_data.h"
#include "io/owned_output.h"
#include "util/cli.h"

namespace {

const char* kUsage =
    "Makes a far-field copy of a Kaldi data directory with the options and meaning of Kaldi's\n"
    "steps/data/reverberate_data_dir.py (docs/kaldi-reverberation.md): each recording convolved with\n"
    "an RIR drawn from the RIR lists (room by room), plus the isotropic noise of that room and 1..N\n"
    "point-source noises, each convolved with another RIR of the same room.\n"
    "\n"
    "Usage: reverberate-data [options] <in-data-dir> <out-data-dir>\n"
    "e.g.\n"
    "  reverberate-data --rir-set-parameters '0.5, RIRS_NOISES/simulated_rirs/smallroom/rir_list' \\\n"
    "    --rir-set-parameters '0.5, RIRS_NOISES/simulated_rirs/mediumroom/rir_list' \\\n"
    "    --noise-set-parameters RIRS_NOISES/pointsource_noises/noise_list \\\n"
    "    --foreground-snrs 20:10:15:5:0 --background-snrs 20:10:15:5:0 --max-noises-per-minute 2 \\\n"
    "    --num-replications 2 --random-seed 1 data/train data/train_rvb\n"
    "  # the paper's benchmark (tsrir extensions): one unreverberated noise per recording, a random\n"
    "  # offset, looped, SNR uniform in [1, 2) dB, 16-bit wavs instead of pipes\n"
    "  reverberate-data --rir-set-parameters rir.scp --noise-set-parameters noise.scp \\\n"
    "    --background-snrs 1..2 --max-noises-per-recording 1 --point-source-noise-rir none \\\n"
    "    --noise-start random --write-wavs exp/rvb_wavs --num-threads 2 data/test data/test_rvb\n"
    "\n"
    "Inputs: wav.scp and utt2spk (text, segments, utt2uniq, spk2utt, reco2file_and_channel and vad.scp\n"
    "are carried over when present); durations from reco2dur, else measured (the input dir is never\n"
    "written). Lists are Kaldi rir_list / noise_list files or scps (<id> <rx>; a noise scp lists\n"
    "point-source background noises). Set weights, --probability and the smoothing weights follow\n"
    "Kaldi's formulas. The same RIR or noise id in two lists (or one list twice) is accepted with a\n"
    "warning and the entries are kept apart; an empty noise list adds no noise; a '#' line in a list\n"
    "is an error, as in Kaldi. Choices are drawn per recording from (seed, copy, id), so any\n"
    "--num-threads gives the same directory (statistically, not bit-for-bit, equal to Kaldi's).\n"
    "\n"
    "Per recording (Kaldi's rules): a room by the summed probability of its RIRs and an RIR in it; the\n"
    "speech is reverberated with probability --speech-rvb-probability; an isotropic noise linked to\n"
    "the room is added with probability --isotropic-noise-addition-probability (also to recordings\n"
    "left unreverberated), extended to the recording from time 0 at a --background-snrs SNR; with\n"
    "probability --pointsource-noise-addition-probability, 1..floor(--max-noises-per-minute *\n"
    "duration / 60) point-source noises (none for shorter recordings), each through an RIR of the\n"
    "same room: background ones extended from time 0 at a --background-snrs SNR, foreground ones\n"
    "added once at a start time uniform over the recording at a --foreground-snrs SNR.\n"
    "SNR lists: Kaldi's '20:10:0' is a list walked cyclically in an order shuffled once; a range is\n"
    "written 'lo..hi' (uniform in [lo, hi) dB per noise; tsrir extension).\n"
    "SNR reference (--snr-reference): early (default, Kaldi's): the speech convolved with the RIR's\n"
    "direct path and early reflections (1 ms before to 50 ms after its largest sample); full: the\n"
    "whole reverberant speech.\n"
    "\n"
    "Output: <out-data-dir> with ids <prefix><copy>-<id> (Kaldi's; unchanged without a prefix), sorted\n"
    "tables, utt2uniq (new id -> original), regenerated spk2utt, reco2dur (with --shift-output=true,\n"
    "the inputs' durations); checked like utils/validate_data_dir.sh --no-feats and written to a\n"
    "temporary directory renamed at the end, so a failure never leaves a partial directory.\n"
    "wav.scp: without --write-wavs every entry is a pipe in Kaldi's form that regenerates the\n"
    "recording on the fly,\n"
    "  [<source pipe> |] wav-reverberate --shift-output=true --impulse-response=<rir>\n"
    "    --additive-signals='<noise>,wav-reverberate --impulse-response=<rir2> --duration=<s> <noise2> - |'\n"
    "    --start-times=0,0 --snrs=10,0 <source wav or -> - |\n"
    "  (all paths shell-quoted; the random draws are written out, so each pipe is deterministic).\n"
    "  Pipes run --pipe-program (default: wav-reverberate next to this program). Kaldi's own binary\n"
    "  runs them too; --noise-start=random and --snr-reference=full need ours and are refused for\n"
    "  another program (--pipe-dialect=auto|tsrir|kaldi overrides that guess).\n"
    "  With --write-wavs=<dir>, 16-bit wavs <dir>/<new-id>.wav are written (any toolkit can read them);\n"
    "  the same seed gives the same audio in both modes. Relative RIR/noise paths are used as given,\n"
    "  as Kaldi does: pipes must run from the same directory.\n"
    "One rate per data dir: --sample-rate (Kaldi's --source-sampling-rate), else the first recording's.\n"
    "RIRs and noises are resampled to it in both modes; a recording at another rate is resampled when\n"
    "--sample-rate was given (in pipes by wav-reverberate --sample-rate) and refused otherwise.\n"
    "Long recordings: with --write-wavs, those beyond --max-in-memory-duration (default 300 s) are\n"
    "read in passes with memory independent of their length and give the same wav.\n";

}  // namespace

int main(int argc, char** argv) {
  // Every utterance allocates and frees ~1 MB buffers; with glibc's defaults each one is a fresh
  // mmap whose pages fault in again (~7% of the run). Keep freed memory in the heap instead
  // (32 MB is the largest threshold glibc accepts on 64-bit: a larger value is ignored).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  return tsrir::run_program("reverberate-data", [&]() {
    tsrir::CommandLine cl("reverberate-data", kUsage);
    tsrir::ReverberateDataOptions o;
    o.Register(&cl);
    tsrir::OutputPolicy policy(cl.program());
    policy.Register(&cl);
    cl.accept_separate_boolean_values();  // "--shift-output true", as Kaldi's reverberate_data_dir.py
    std::vector<std::string> dirs = cl.parse(argc, argv, 2, 2);
    tsrir::install_output_policy(policy);
    tsrir::reverberate_data_dir(dirs[0], dirs[1], o);
    return 0;
  });
}
