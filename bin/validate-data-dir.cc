// validate-data-dir: the checks of Kaldi's utils/validate_data_dir.sh --no-feats, without Kaldi.
#include "io/validate_data_dir_program.h"
#include "util/cli.h"

int main(int argc, char** argv) {
  return tsrir::run_program("validate-data-dir", [&]() {
    tsrir::CommandLine cli(
        "validate-data-dir",
        "Checks a Kaldi data directory the way Kaldi's utils/validate_data_dir.sh --no-feats does:\n"
        "wav.scp, utt2spk and spk2utt present, every table sorted and unique under LC_ALL=C,\n"
        "utt2spk also sorted by speaker and agreeing with spk2utt, segments (4 fields, end > start,\n"
        "known recordings), text covering every utterance (unless --no-text), utt2uniq and reco2dur\n"
        "covering theirs, no '~' in wav.scp; then (tsrir) one sample rate for every recording (files\n"
        "from their headers; pipes with --probe-pipes). Prints each problem on stderr; exit status 1\n"
        "if any.\n"
        "Features are never checked (--no-feats is accepted for the same command line as Kaldi's).\n"
        "\n"
        "Usage: validate-data-dir [--no-text] [--no-feats] [--check-rates=false] [--probe-pipes] <data-dir>\n"
        "Example:\n"
        "  validate-data-dir --no-feats data/test_clean_rvb_real\n");
    tsrir::ValidateDataDirOptions options;
    options.Register(&cli);
    const auto args = cli.parse(argc, argv, 1, 1);
    return tsrir::run_validate_data_dir(options, args[0]);
  });
}
