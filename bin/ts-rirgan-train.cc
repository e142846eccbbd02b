// ts-rirgan-train: trains TS-RIRGAN (a 1-D CycleGAN) on unpaired real and synthetic RIR sets.
#include <string>

#include "gan/ts_rirgan.h"
#include "io/owned_output.h"
#include "util/cli.h"

int main(int argc, char** argv) {
  return tsrir::run_program("ts-rirgan-train", [&]() {
    tsrir::GanTrainOptions o;
    tsrir::CommandLine cli(
        "ts-rirgan-train",
        "Trains TS-RIRGAN (Ratnarajah et al., ASRU 2021) on two unpaired RIR sets: G_SR translates\n"
        "synthetic RIRs into real-like ones, G_RS the reverse. RIRs are resampled to 16 kHz, cut to\n"
        "their first 16384 samples (with a warning) or zero-padded, and peak-normalised, as the\n"
        "original. Losses, weights and RMSProp follow the original; --width=64 is the paper's model.\n"
        "<model-dir> receives settings.txt, checkpoint.pt (networks + optimiser state, written every\n"
        "--checkpoint-every steps, at the end and on SIGINT/SIGTERM) and loss_log.csv (one row per step).\n"
        "Deterministic for a given --seed and --num-threads on CPU; --resume continues exactly.\n"
        "Departures from the original (off by default): --init=he replaces the original's Glorot-uniform\n"
        "kernels with He-uniform ones, so that small models (width 4-16) trained for a few hundred CPU\n"
        "steps start with an output that depends on the input (with Glorot the 13 un-normalised ReLU\n"
        "layers shrink the signal ~3e-4); --rmsprop-initial-ms=0 starts RMSProp's mean square at 0\n"
        "(torch/Keras) instead of TF1's 1, which makes the first ~130 steps almost no-ops;\n"
        "--warmup-steps=N ramps the learning rate over N steps (without it, RMSProp's first updates\n"
        "can switch whole ReLU layers of a small generator off for good: a constant output);\n"
        "--cycle-weight/--identity-weight change the L1 weights; --decoder=light builds the lighter\n"
        "up path that the original's code comments describe (its code builds --decoder=original).\n"
        "\n"
        "Usage: ts-rirgan-train [options] --real=<rir-scp> --synthetic=<rir-scp> <model-dir>\n"
        "Example:\n"
        "  ts-rirgan-train --real=data/real/rir.scp --synthetic=data/gas/rir.scp \\\n"
        "      --steps=20000 --batch-size=64 --num-threads=8 exp/tsrirgan\n");
    cli.option("real", &o.real_list, "Real RIRs: rir scp, rir_list or one audio file");
    cli.option("synthetic", &o.synthetic_list, "Synthetic RIRs: rir scp, rir_list or one audio file");
    cli.option("steps", &o.steps, "Total training iterations (each: 2x2 D updates, 2 G updates)");
    cli.option("width", &o.width, "Model width (64 = the paper's model; 4-16 for CPU experiments)");
    cli.option("decoder", &o.decoder,
               "Generator up path: original (16w,8w,4w channels: the original's code) or light "
               "(4w,2w,w: its code comments; 41.4 M instead of 66.6 M parameters at width 64, 1/3 of the FLOPs)");
    cli.option("batch-size", &o.batch_size, "RIRs per batch (the paper's is 64)");
    cli.option("seed", &o.seed, "Random seed (initialisation and batch order)");
    cli.option("num-threads", &o.num_threads, "CPU threads for LibTorch (OpenBLAS is kept at 1)");
    cli.option("checkpoint-every", &o.checkpoint_every, "Write checkpoint.pt every N steps");
    cli.flag("resume", &o.resume, "Continue from <model-dir>/checkpoint.pt (same settings required)");
    cli.option("device", &o.device, "cpu or cuda (needs a LibTorch with CUDA and a GPU)");
    cli.option("learning-rate", &o.learning_rate, "RMSProp learning rate (the paper's: 3e-5)");
    cli.option("disc-updates", &o.disc_updates, "Discriminator updates per generator update");
    cli.option("init", &o.init, "Kernel init of a new model: glorot (the original) or he (small CPU models)");
    cli.option("rmsprop-initial-ms", &o.rmsprop_initial_ms, "RMSProp's initial mean square of a new model: 1 (TF1, the original) or 0");
    cli.option("cycle-weight", &o.cycle_weight, "Generator loss weight per cycle L1 term (the original's: 250)");
    cli.option("identity-weight", &o.identity_weight, "Generator loss weight of the identity L1 term (the original's: 175)");
    cli.option("warmup-steps", &o.warmup_steps,
               "Ramp the learning rate linearly over the first N steps (0 = none, the original)");
    cli.option("precision", &o.precision,
               "float32 (the original) or bfloat16: CPU autocast, bfloat16 convolutions with float32 "
               "weights, gradients and losses; ~2x faster on CPUs with AVX512-BF16/AMX");
    cli.option("progress-interval", &o.progress_interval_s, "Seconds between progress lines on stderr");
    tsrir::register_output_options(&cli);
    const auto args = cli.parse(argc, argv, 1, 1);
    o.model_dir = args[0];
    const tsrir::GanTrainResult r = tsrir::train_ts_rirgan(o);
    return r.interrupted ? 130 : 0;
  });
}
