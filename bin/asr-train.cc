// asr-train: trains the compact CTC character recogniser of the downstream experiment.
#include <string>

#include "asr/asr.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/strings.h"

int main(int argc, char** argv) {
  return tsrir::run_program("asr-train", [&]() {
    tsrir::AsrTrainOptions o;
    tsrir::CommandLine cli(
        "asr-train",
        "Trains a compact CTC character recogniser on a Kaldi data dir (wav.scp with files or pipes,\n"
        "text, utt2spk; segments optional): 40 log-mel features (25/10 ms, the toolkit's FFT) with\n"
        "per-utterance mean/variance normalisation -> 1-D convolutions (the first subsamples time) ->\n"
        "layer norm -> bidirectional GRU or LSTM layers -> characters a-z, ' and space, trained with\n"
        "CTC, Adam and SpecAugment-style time/frequency masks. Transcripts are lower-cased and every\n"
        "character outside [a-z'] becomes a word boundary.\n"
        "<model-dir> receives settings.txt, checkpoint.pt (model + optimiser, written atomically after\n"
        "every epoch, at --max-minutes and on SIGINT/SIGTERM) and loss_log.csv (one row per step).\n"
        "Deterministic for a given --seed and --num-threads on the CPU (--device=cuda trains on a GPU,\n"
        "not bit-reproducibly); --resume continues exactly where the checkpoint stopped (also\n"
        "mid-epoch, also on the other device), and may raise --epochs.\n"
        "\n"
        "Usage: asr-train [options] <data-dir> <model-dir>\n"
        "Examples:\n"
        "  asr-train --epochs=20 --num-threads=2 --seed=1 data/train_rvb_real exp/asr/real\n"
        "  asr-train --config=conf/asr-train-proxy.conf --seed=1 data/train_rvb_real exp/asr/real\n");
    o.Register(&cli);
    tsrir::OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const auto args = cli.parse(argc, argv, 2, 2);
    tsrir::install_output_policy(policy);
    o.data_dir = args[0];
    o.model_dir = args[1];
    const tsrir::AsrTrainResult r = tsrir::train_asr(o);
    tsrir::log_info("trained " + std::to_string(r.epochs_done) + " epoch(s), " + std::to_string(r.steps_done) +
                    " steps in " + tsrir::format_double(r.train_s, 4) + " s (this run); last epoch loss " +
                    tsrir::format_double(r.last_epoch_loss, 4) + "; peak memory " +
                    tsrir::format_double(r.peak_rss_mb, 4) + " MB");
    return r.interrupted ? 130 : 0;
  });
}
