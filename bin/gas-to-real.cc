// gas-to-real: translates synthetic RIRs into real-like ones with a trained TS-RIRGAN.
#include <string>

#include "gan/ts_rirgan.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/strings.h"

int main(int argc, char** argv) {
  return tsrir::run_program("gas-to-real", [&]() {
    tsrir::GanTranslateOptions o;
    tsrir::CommandLine cli(
        "gas-to-real",
        "Translates RIRs with a trained TS-RIRGAN generator (G_SR: synthetic -> real by default).\n"
        "Each output keeps its input's id: <out-dir>/<id>.wav, rir.scp and rir_list (room ids kept).\n"
        "Conventions: inputs are resampled to 16 kHz, cut to their first 16384 samples (warning) or\n"
        "zero-padded, and peak-normalised before the generator, as in training. Outputs are 16 kHz.\n"
        "  Length: --keep-length=16000 keeps the first 16000 of the 16384 generated samples (the\n"
        "          original's generator.py); a number in [1, 16384] keeps that many; 'input' keeps the\n"
        "          input's length at 16 kHz (at most 16384).\n"
        "  Level:  by default the generator's output as is (peak near 1 like the peak-normalised\n"
        "          training data: tanh for --generator=original; for band-gain (the default) and residual,\n"
        "          what the generator made of its peak-normalised input, scaled to 32767/32768 where it\n"
        "          passes that), as the original; --restore-level scales each output\n"
        "          by its input's peak |x|.\n"
        "  Model:  the generator file training writes beside the checkpoint (generator-g_real.pt,\n"
        "          generator-g_synthetic.pt: the default weights alone) when it was written from that\n"
        "          checkpoint, else the checkpoint (--use-last-weights of an averaged model, an older\n"
        "          model dir, a checkpoint copied alone).\n"
        "\n"
        "Usage: gas-to-real [options] --model=<model-dir-or-checkpoint> <in-rir-scp> <out-dir>\n"
        "Example:\n"
        "  gas-to-real --model=exp/tsrirgan --batch-size=32 --num-threads=4 data/gas/rir.scp data/gsr_gas\n");
    o.Register(&cli);
    tsrir::OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const auto args = cli.parse(argc, argv, 2, 2);
    tsrir::install_output_policy(policy);
    if (o.model.empty()) throw tsrir::Error("--model is required");
    o.input_list = args[0];
    o.out_dir = args[1];
    const tsrir::GanTranslateResult r = tsrir::translate_rirs(o);
    tsrir::log_info("translated " + std::to_string(r.num_rirs) + " RIRs into " + o.out_dir + " in " +
                    tsrir::format_double(r.translate_s, 3) + " s (model load " +
                    tsrir::format_double(r.model_load_s, 3) + " s, " +
                    tsrir::format_double(r.num_rirs / r.translate_s, 3) + " RIRs/s)");
    return 0;
  });
}
