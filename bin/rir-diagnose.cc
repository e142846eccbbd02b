// rir-diagnose: where and why the toolkit's simulation departs from measured RIRs, the model
// extension that fixes it, and the gain on held-out RIRs.
#include <string>
#include <vector>

#include "diagnose/diagnose.h"
#include "diagnose/measured_set.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/error.h"
#include <iostream>

int main(int argc, char** argv) {
  using namespace tsrir;
  return run_program("rir-diagnose", [&]() {
    const std::string usage =
        "Simulates the set-ups of measured RIRs with the toolkit's model, tests the set for each effect of its\n"
        "catalog (room_modes, air_absorption, band_absorption, transducer_response, noise_floor,\n"
        "diffuse_scattering, time_offset), fits the model extension of every detected effect on half of the\n"
        "RIRs (alternating ids within each room) and reports the error of baseline and extended model on the\n"
        "other half. Writes <out-dir>/findings.json, <out-dir>/report.html and <out-dir>/extended_models\n"
        "(<room-id> <model spec> for rir-simulate --model); prints a summary on stdout.\n\n"
        "Usage: rir-diagnose [options] <room-list> <measured-rir-scp> <out-dir>\n"
        "  <room-list>: as for rir-simulate, one line per measured RIR id (extra lines are ignored)\n"
        "  <measured-rir-scp>: <rir-id> <rxfilename> (or a Kaldi rir_list)\n"
        "Example:\n"
        "  rir-diagnose --fs=16000 --num-threads=2 rooms.txt measured/rir.scp exp/diagnose\n";
    CommandLine cli("rir-diagnose", usage);
    diagnose::DiagnoseOptions options;
    int seed = static_cast<int>(options.seed);
    cli.option("fs", &options.sample_rate_hz, "analysis sample rate, Hz (measured RIRs are resampled)");
    cli.option("model", &options.baseline_model, "baseline model (rir-simulate --model syntax)");
    cli.option("seed", &seed, "seed of the simulations (seed, seed+1 for the null calibration, seed+2 for evaluation)");
    cli.option("num-threads", &options.num_threads, "threads");
    register_output_options(&cli);
    const std::vector<std::string> args = cli.parse(argc, argv, 3, 3);
    options.seed = static_cast<uint64_t>(static_cast<int64_t>(seed));
    if (options.num_threads < 1) throw Error("--num-threads must be at least 1");
    std::string command = "rir-diagnose";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    const diagnose::MeasuredSet set = diagnose::load_measured_set(args[0], args[1]);
    const diagnose::Diagnosis d = diagnose::diagnose_set(set.rooms, set.measured, options, set.where);
    std::cout << diagnose::write_diagnosis(d, args[2], command);
    return 0;
  });
}
