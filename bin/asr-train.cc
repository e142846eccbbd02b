// asr-train: trains the compact CTC character recogniser of the downstream experiment.
#include <string>

#include "asr/asr.h"
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
        "Deterministic for a given --seed and --num-threads; --resume continues exactly where the\n"
        "checkpoint stopped (also mid-epoch), and may raise --epochs.\n"
        "\n"
        "Usage: asr-train [options] <data-dir> <model-dir>\n"
        "Example:\n"
        "  asr-train --epochs=20 --num-threads=2 --seed=1 data/train_rvb_real exp/asr/real\n");
    cli.option("epochs", &o.epochs, "Total training epochs (a resumed run continues to this count)");
    cli.option("max-minutes", &o.max_minutes, "Stop after this many minutes of training with a checkpoint (0 = no limit)");
    cli.option("seed", &o.seed, "Random seed (initialisation, batch order, masks, dropout)");
    cli.option("num-threads", &o.num_threads, "CPU threads for LibTorch and feature extraction");
    cli.option("batch-size", &o.batch_size, "Utterances per step (batches group similar lengths)");
    cli.option("learning-rate", &o.learning_rate, "Adam learning rate");
    cli.option("grad-clip", &o.grad_clip, "Gradient norm clip");
    cli.option("conv-layers", &o.model.conv_layers, "1-D convolution layers");
    cli.option("conv-channels", &o.model.conv_channels, "Channels of the convolutions");
    cli.option("conv-kernel", &o.model.conv_kernel, "Kernel width of the convolutions (odd)");
    cli.option("subsampling", &o.model.subsampling, "Time stride of the first convolution");
    cli.option("rnn-type", &o.model.rnn_type, "gru or lstm");
    cli.option("rnn-layers", &o.model.rnn_layers, "Bidirectional recurrent layers");
    cli.option("rnn-hidden", &o.model.rnn_hidden, "Hidden units per direction");
    cli.option("dropout", &o.model.dropout, "Dropout after the convolutions, between and after the recurrent layers");
    cli.option("time-masks", &o.time_masks, "SpecAugment time masks per utterance");
    cli.option("max-time-mask", &o.max_time_mask, "Longest time mask as a fraction of the utterance");
    cli.option("freq-masks", &o.freq_masks, "SpecAugment frequency masks per utterance");
    cli.option("max-freq-mask", &o.max_freq_mask, "Widest frequency mask (mel bins)");
    cli.option("num-mel-bins", &o.features.num_mel_bins, "Mel filters");
    cli.option("sample-rate", &o.features.sample_rate_hz, "Audio is resampled to this rate (Hz)");
    cli.option("low-freq", &o.features.low_hz, "Lowest mel filter edge (Hz)");
    cli.option("high-freq", &o.features.high_hz, "Highest mel filter edge (Hz; <= 0: offset from Nyquist)");
    cli.flag("resume", &o.resume, "Continue from <model-dir>/checkpoint.pt (same settings required)");
    cli.option("progress-interval", &o.progress_interval_s, "Seconds between progress lines on stderr");
    const auto args = cli.parse(argc, argv, 2, 2);
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
