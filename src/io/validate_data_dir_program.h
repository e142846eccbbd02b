// The validate-data-dir program body: Kaldi's utils/validate_data_dir.sh --no-feats checks
// (validate_data_dir in data_dir.h) with the program's options registering themselves.
#pragma once
#include <string>

#include "util/options.h"

namespace tsrir {

struct ValidateDataDirOptions {
  bool no_text = false;   // text may be absent (still checked when present)
  bool no_feats = false;  // Kaldi's flag; features are never checked, it only silences the warning

  void Register(OptionsItf* opts);
};

// Prints each problem on stderr ("validate-data-dir: <problem>"); returns 0 when `dir` is valid,
// 1 otherwise. Throws Error when `dir` is not a directory.
int run_validate_data_dir(const ValidateDataDirOptions& options, const std::string& dir);

}  // namespace tsrir
