// Kaldi's RIR list and noise list lines (steps/data/reverberate_data_dir.py formats), plus the
// "scp" alternative (<id> <rxfilename>) accepted wherever a list is.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "util/options.h"

namespace tsrir {

// A point-source noise's --bg-fg-type: background (extended over the recording from its start) or
// foreground (added once at a random time).
enum class BgFgType { kBackground, kForeground };
const Choices<BgFgType>& bg_fg_type_choices();  // "background" | "foreground"

struct RirListEntry {
  std::string rir_id;
  std::string room_id;
  std::string receiver_position_id;
  std::string source_position_id;
  std::optional<double> rt60, drr, cte, probability;
  std::string rxfilename;
  int line = 0;
};

struct NoiseListEntry {
  std::string noise_id;
  std::string noise_type;        // "isotropic" | "point-source"
  BgFgType bg_fg_type = BgFgType::kBackground;
  std::string room_linkage;      // required for isotropic
  std::optional<double> probability;
  std::string rxfilename;
  int line = 0;
};

// Splits a line the way Python's shlex.split does (quotes, backslash escapes; no comments).
std::vector<std::string> shlex_split(const std::string& line, const std::string& context);

RirListEntry parse_rir_list_line(const std::string& line, const std::string& context);
NoiseListEntry parse_noise_list_line(const std::string& line, const std::string& context);

// Whole files: blank lines skipped; duplicate ids within one file are errors with file:line; a line
// starting with "#" is an error (Kaldi's script has no comments in these lists and fails on it); an
// empty noise list gives no entries (Kaldi proceeds without its noises), an empty RIR list is an error. A file whose
// first non-blank line does not start with "--" is read as an scp (<id> <rxfilename>): RIRs get
// room id = rir id, noises become point-source background noises.
std::vector<RirListEntry> read_rir_list(const std::string& path);
std::vector<NoiseListEntry> read_noise_list(const std::string& path);

// Formats a line Kaldi's scripts can read back (paths shell-quoted when needed).
std::string format_rir_list_line(const RirListEntry& e);

}  // namespace tsrir
