// rir-diagnose: where and why the toolkit's simulation departs from measured RIRs, the model
// extension that fixes it, and the gain on held-out RIRs.
#include <string>
#include <vector>

#include "diagnose/diagnose_program.h"
#include "io/owned_output.h"
#include "util/cli.h"

int main(int argc, char** argv) {
  using namespace tsrir;
  return run_program("rir-diagnose", [&]() {
    CommandLine cli("rir-diagnose", diagnose::rir_diagnose_usage());
    diagnose::DiagnoseOptions options;
    options.Register(&cli);
    OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const std::vector<std::string> args = cli.parse(argc, argv, 3, 3);
    install_output_policy(policy);
    std::string command = "rir-diagnose";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    return diagnose::run_rir_diagnose(options, args, command);
  });
}
