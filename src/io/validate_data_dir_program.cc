#include "io/validate_data_dir_program.h"

#include <filesystem>
#include <iostream>

#include "io/audio_io.h"
#include "io/data_dir.h"
#include "io/rxfile.h"
#include "util/error.h"
#include "util/log.h"
#include "util/strings.h"

namespace tsrir {

void ValidateDataDirOptions::Register(OptionsItf* opts) {
  opts->Register("no-text", &no_text, "text may be absent (it is still checked when present)");
  opts->Register("no-feats", &no_feats, "accepted for Kaldi's command line; features are never checked");
  opts->Register("check-rates", &check_rates,
                 "the recordings must share one sample rate (files: from their headers; tsrir extension)");
  opts->Register("probe-pipes", &probe_pipes,
                 "with --check-rates, also run and read wav.scp's pipes (decodes them; tsrir extension)");
}

std::string mixed_sample_rates(const std::string& dir, const std::map<std::string, std::string>& wav_scp,
                               bool probe_pipes) {
  std::map<double, std::pair<size_t, std::string>> rates;  // Hz -> (recordings, first id)
  size_t unreadable = 0;
  for (const auto& [id, rx] : wav_scp) {
    if (!probe_pipes && (is_pipe_rxfilename(rx) || trim(rx) == "-")) continue;
    AudioInfo info;
    // Kaldi's checks are of the tables, not the audio (a dir may list files of another machine):
    // an unreadable recording is left out of the rate check, not a problem.
    try {
      if (is_pipe_rxfilename(rx)) read_audio_channels(rx, &info, dir + "/wav.scp: recording '" + id + "'");
      else info = probe_audio(trim(rx));
    } catch (const Error&) {
      ++unreadable;
      continue;
    }
    auto& entry = rates[info.sample_rate_hz];
    if (entry.first++ == 0) entry.second = id;
  }
  if (unreadable > 0)
    log_info(dir + "/wav.scp: " + std::to_string(unreadable) +
             " recording(s) could not be read: their rates are not checked");
  if (rates.size() < 2) return "";
  std::string text = dir + "/wav.scp: mixed sample rates:";
  for (const auto& [hz, seen] : rates)
    text += " " + format_double(hz) + " Hz (" + std::to_string(seen.first) + " recording(s), e.g. '" + seen.second + "')";
  return text + "; a data dir holds one rate (reverberate-data --sample-rate resamples to one)";
}

int run_validate_data_dir(const ValidateDataDirOptions& options, const std::string& dir) {
  if (!std::filesystem::is_directory(dir)) throw Error(dir + ": no such directory");
  if (!options.no_feats && std::filesystem::exists(std::filesystem::path(dir) / "feats.scp")) {
    log_warning(dir + "/feats.scp exists but is not checked (use Kaldi's validate_data_dir.sh for features)");
  }
  auto problems = validate_data_dir(dir, !options.no_text);
  if (options.check_rates && problems.empty()) {
    const std::string mixed = mixed_sample_rates(dir, read_data_dir(dir).wav_scp, options.probe_pipes);
    if (!mixed.empty()) problems.push_back(mixed);
  }
  for (const auto& p : problems) std::cerr << "validate-data-dir: " << p << "\n";
  if (!problems.empty()) {
    std::cerr << "validate-data-dir: " << dir << ": " << problems.size() << " problem(s)\n";
    return 1;
  }
  log_info(dir + ": valid");
  return 0;
}

}  // namespace tsrir
