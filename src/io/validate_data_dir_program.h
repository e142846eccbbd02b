// The validate-data-dir program body: Kaldi's utils/validate_data_dir.sh --no-feats checks
// (validate_data_dir in data_dir.h) with the program's options registering themselves.
#pragma once
#include <map>
#include <string>

#include "util/options.h"

namespace tsrir {

struct ValidateDataDirOptions {
  bool no_text = false;   // text may be absent (still checked when present)
  bool no_feats = false;  // Kaldi's flag; features are never checked, it only silences the warning
  // The recordings' sample rates must agree (files: from their headers); true: pipes are run and
  // read too (the whole corpus decoded once). Kaldi's script does not check rates.
  bool check_rates = true;
  bool probe_pipes = false;

  void Register(OptionsItf* opts);
};

// The problem "mixed sample rates: ..." when the recordings of `wav_scp` (files; pipes too with
// `probe_pipes`) are not all at one rate, naming each rate, its count and an example; "" otherwise.
// Recordings that cannot be read are left out (logged): Kaldi's checks are of the tables.
std::string mixed_sample_rates(const std::string& dir, const std::map<std::string, std::string>& wav_scp,
                               bool probe_pipes);

// Prints each problem on stderr ("validate-data-dir: <problem>"); returns 0 when `dir` is valid,
// 1 otherwise. Throws Error when `dir` is not a directory.
int run_validate_data_dir(const ValidateDataDirOptions& options, const std::string& dir);

}  // namespace tsrir
