#include "io/validate_data_dir_program.h"

#include <filesystem>
#include <iostream>

#include "io/data_dir.h"
#include "util/error.h"
#include "util/log.h"

namespace tsrir {

void ValidateDataDirOptions::Register(OptionsItf* opts) {
  opts->Register("no-text", &no_text, "text may be absent (it is still checked when present)");
  opts->Register("no-feats", &no_feats, "accepted for Kaldi's command line; features are never checked");
}

int run_validate_data_dir(const ValidateDataDirOptions& options, const std::string& dir) {
  if (!std::filesystem::is_directory(dir)) throw Error(dir + ": no such directory");
  if (!options.no_feats && std::filesystem::exists(std::filesystem::path(dir) / "feats.scp")) {
    log_warning(dir + "/feats.scp exists but is not checked (use Kaldi's validate_data_dir.sh for features)");
  }
  const auto problems = validate_data_dir(dir, !options.no_text);
  for (const auto& p : problems) std::cerr << "validate-data-dir: " << p << "\n";
  if (!problems.empty()) {
    std::cerr << "validate-data-dir: " << dir << ": " << problems.size() << " problem(s)\n";
    return 1;
  }
  log_info(dir + ": valid");
  return 0;
}

}  // namespace tsrir
