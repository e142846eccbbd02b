// ts-rirgan-train: trains TS-RIRGAN (a 1-D CycleGAN) on unpaired real and synthetic RIR sets.
#include <iostream>
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
        "original. The defaults are issue 34's whole-band translator, which passed the translation-\n"
        "fidelity suite (tests/gan, bench/gan/fidelity_trajectory.sh: each output gains the real\n"
        "domain's hidden effect - modes below 200 Hz, a faster high-band decay, a stronger direct sound or\n"
        "early energy above 2 kHz - while keeping its own input's onset, fine structure and every\n"
        "parameter the effect leaves alone) on at least 4 of 5 seeds per kind at width 16, batch 4, 2000\n"
        "steps (bench/RESULTS.md). They depart from the paper in:\n"
        "  --generator=band-gain: output = the input's own band signals (11 half-octave bands) times a\n"
        "      smooth gain per band and per time knot after the input's direct sound (direct sound,\n"
        "      3 ms ... 768 ms), plus a learned waveform correction low-passed at --correction-max-hz=500\n"
        "      (room modes), scaled to the input's peak: the direct sound, early energy and decay of every\n"
        "      band can change while the fine structure stays the input's;\n"
        "  --gain-weight=1, --correction-weight=1: L2 penalties on the log gains and on the correction's\n"
        "      energy, so a translation changes only what the discriminators ask for;\n"
        "  --identity-gain-weight=10 (--identity-direct-bands=1): the log gains a generator predicts for\n"
        "      its own domain's RIRs, after the direct sound and at it below 250 Hz, are held at 0 (a gain\n"
        "      identity that sees a band's quiet tail, which the waveform identity does not);\n"
        "  --disc-view=waveform+envelope: each discriminator also reads every band's level in dB per 8 ms;\n"
        "  --disc-augment=shift-gain-polarity: what a discriminator reads is delayed, scaled and flipped\n"
        "      at random (small training sets);\n"
        "  --generator-average-decay=0.995: gas-to-real translates with the generators' weights averaged\n"
        "      over the last ~200 steps (--use-last-weights: the last step's);\n"
        "  --generator-update=joint: both generators from one forward, one summed loss (CycleGAN's code);\n"
        "  --identity-weight=0 and --cycle-weight=25 (paper 175 and 250: at those weights the L1 terms\n"
        "      hold the translation at the identity);\n"
        "  --disc-learning-rate=1e-4 (paper: the generators' 3e-5), --disc-updates=1 (paper 2),\n"
        "  --decoder=light (the up path the original's code comments describe, 1/3 of the FLOPs),\n"
        "  --init=he (paper glorot), --rmsprop-initial-ms=0 (paper 1, TF1), --warmup-steps=100 (paper 0).\n"
        "The defaults before 2026-12-04 (issue 17's residual generator, nothing above 500 Hz changed):\n"
        "--config=conf/ts-rirgan-residual.conf.\n"
        "The paper's exact configuration: --config=conf/ts-rirgan-paper.conf. Losses, layers and batch\n"
        "size 64 are the paper's; --width=64 is the paper's model.\n"
        "<model-dir> receives settings.txt, checkpoint.pt (networks + optimiser state, written every\n"
        "--checkpoint-every steps, at the end and on SIGINT/SIGTERM), loss_log.csv (one row per step)\n"
        "and loss_curves.svg (the losses drawn; written whenever training stops). Every\n"
        "--collapse-check-every steps G_SR translates 8 training RIRs; training stops with an error if\n"
        "the outputs are silent or nearly equal across inputs (a collapsed generator).\n"
        "Deterministic for a given --seed and --num-threads on CPU; --resume continues exactly.\n"
        "\n"
        "Usage: ts-rirgan-train [options] --real=<rir-scp> --synthetic=<rir-scp> <model-dir>\n"
        "Example:\n"
        "  ts-rirgan-train --real=data/real/rir.scp --synthetic=data/gas/rir.scp \\\n"
        "      --steps=20000 --batch-size=64 --num-threads=8 exp/tsrirgan\n");
    o.Register(&cli);
    tsrir::OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const auto args = cli.parse(argc, argv, 1, 1);
    tsrir::install_output_policy(policy);
    o.model_dir = args[0];
    if (o.print_settings) {
      std::cout << tsrir::gan_settings_text(tsrir::settings_to_store(o));
      return 0;
    }
    const tsrir::GanTrainResult r = tsrir::train_ts_rirgan(o);
    return r.interrupted ? 130 : 0;
  });
}
