#include "diagnose/diagnose_program.h"

#include <iostream>

#include "diagnose/diagnose.h"
#include "diagnose/effect.h"
#include "diagnose/measured_set.h"

namespace tsrir::diagnose {

std::string rir_diagnose_usage() {
  std::string catalog;
  for (const std::string& name : effect_registry().names()) catalog += (catalog.empty() ? "" : ", ") + name;
  return "Simulates the set-ups of measured RIRs with the toolkit's model, tests the set for each effect of its\n"
         "catalog (" + catalog + ", below),\n"
         "fits the model extension of every detected effect on half of the RIRs (alternating ids within each room)\n"
         "and reports the error of baseline and extended model on the other half. Writes <out-dir>/findings.json,\n"
         "<out-dir>/report.html and <out-dir>/extended_models (<room-id> <model spec> for rir-simulate --model);\n"
         "prints a summary on stdout.\n\n"
         "Usage: rir-diagnose [options] <room-list> <measured-rir-scp> <out-dir>\n"
         "  <room-list>: as for rir-simulate, one line per measured RIR id (extra lines are ignored)\n"
         "  <measured-rir-scp>: <rir-id> <rxfilename> (or a Kaldi rir_list)\n"
         "Example:\n"
         "  rir-diagnose --sample-rate=16000 --num-threads=2 rooms.txt measured/rir.scp exp/diagnose\n\n" +
         effects_help(effect_registry());
}

int run_rir_diagnose(const DiagnoseOptions& options, const std::vector<std::string>& args, const std::string& command_line) {
  options.Validate();
  const MeasuredSet set = load_measured_set(args.at(0), args.at(1));
  const Diagnosis d = diagnose_set(set.rooms, set.measured, options, set.where);
  std::cout << write_diagnosis(d, args.at(2), command_line);
  return 0;
}

}  // namespace tsrir::diagnose
