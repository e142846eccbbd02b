// validate-data-dir: the checks of Kaldi's utils/validate_data_dir.sh --no-feats, without Kaldi.
#include <filesystem>
#include <iostream>
#include <string>

#include "io/data_dir.h"
#include "util/cli.h"
#include "util/error.h"

int main(int argc, char** argv) {
  return tsrir::run_program("validate-data-dir", [&]() {
    tsrir::CommandLine cli(
        "validate-data-dir",
        "Checks a Kaldi data directory the way Kaldi's utils/validate_data_dir.sh --no-feats does:\n"
        "wav.scp, utt2spk and spk2utt present, every table sorted and unique under LC_ALL=C,\n"
        "utt2spk also sorted by speaker and agreeing with spk2utt, segments (4 fields, end > start,\n"
        "known recordings), text covering every utterance (unless --no-text), utt2uniq and reco2dur\n"
        "covering theirs, no '~' in wav.scp. Prints each problem on stderr; exit status 1 if any.\n"
        "Features are never checked (--no-feats is accepted for the same command line as Kaldi's).\n"
        "\n"
        "Usage: validate-data-dir [--no-text] [--no-feats] <data-dir>\n"
        "Example:\n"
        "  validate-data-dir --no-feats data/test_clean_rvb_real\n");
    bool no_text = false, no_feats = false;
    cli.flag("no-text", &no_text, "text may be absent (it is still checked when present)");
    cli.flag("no-feats", &no_feats, "accepted for Kaldi's command line; features are never checked");
    const auto args = cli.parse(argc, argv, 1, 1);
    const std::string& dir = args[0];
    if (!std::filesystem::is_directory(dir)) throw tsrir::Error(dir + ": no such directory");
    if (!no_feats && std::filesystem::exists(std::filesystem::path(dir) / "feats.scp")) {
      tsrir::log_warning(dir + "/feats.scp exists but is not checked (use Kaldi's validate_data_dir.sh for features)");
    }
    const auto problems = tsrir::validate_data_dir(dir, !no_text);
    for (const auto& p : problems) std::cerr << "validate-data-dir: " << p << "\n";
    if (!problems.empty()) {
      std::cerr << "validate-data-dir: " << dir << ": " << problems.size() << " problem(s)\n";
      return 1;
    }
    tsrir::log_info(dir + ": valid");
    return 0;
  });
}
