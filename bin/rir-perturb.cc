// rir-perturb: controlled mismatches of RIR sets (the downstream experiment's positive controls).
#include "io/owned_output.h"
#include "perturb/perturb_set.h"
#include "util/cli.h"

int main(int argc, char** argv) {
  return tsrir::run_program("rir-perturb", [&]() {
    tsrir::CommandLine cli(
        "rir-perturb",
        "Changes one acoustic parameter of every RIR of a set by a known amount and keeps the rest of\n"
        "each response as it is: the positive controls of the downstream experiment (training data\n"
        "made with a graded, known mismatch against the real RIRs; docs/results/downstream.md).\n"
        "  --t60-scale=S     the decay after the direct sound re-weighted by exp(-k (t - t_d)) with\n"
        "                    k = 3 ln10 (1/(S T) - 1/T), T the RIR's own T60 (ISO, rir-metrics): the\n"
        "                    T60 becomes S T; for S > 1 the measurement noise after the Lundeby\n"
        "                    intersection is faded out first, and the file keeps its length.\n"
        "  --drr-offset-db=D the direct window (peak -2.5..+2.5 ms) scaled by D dB.\n"
        "  --lf-ringing-db=L 8 damped modes at 40-200 Hz (--lf-min-hz, --lf-max-hz; decay --lf-t60)\n"
        "                    added L dB above the RIR's own energy below --lf-max-hz.\n"
        "Writes <out-dir>/<id>.wav, rir.scp and rir_list (ids and room ids kept) and logs the set's\n"
        "mean T60, DRR and C50 before and after.\n"
        "\n"
        "Usage: rir-perturb [options] <in-rir-scp-or-list> <out-dir>\n"
        "Examples:\n"
        "  rir-perturb --t60-scale=0.33 real_train/rir_list t60x0.33_train\n"
        "  rir-perturb --drr-offset-db=6 --num-threads=2 real_train/rir_list drr+6_train\n"
        "  rir-perturb --lf-ringing-db=10 --seed=3 real_train/rir_list lfring_train\n");
    tsrir::PerturbSetOptions options;
    options.Register(&cli);
    tsrir::OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const auto args = cli.parse(argc, argv, 2, 2);
    tsrir::install_output_policy(policy);
    const tsrir::PerturbSetSummary s = tsrir::perturb_rir_set(args[0], args[1], options);
    tsrir::log_info("perturbed " + tsrir::format_perturb_summary(s) + " into " + args[1]);
    return 0;
  });
}
