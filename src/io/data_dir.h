// A Kaldi data directory: wav.scp, utt2spk, spk2utt and the optional text, segments, reco2dur,
// utt2uniq. Reading checks consistency the way utils/validate_data_dir.sh --no-feats does.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tsrir {

struct Segment {
  std::string recording_id;
  double start_s = 0.0;
  double end_s = 0.0;
};

struct DataDir {
  std::map<std::string, std::string> wav_scp;     // recording id -> rxfilename
  std::map<std::string, std::string> utt2spk;
  std::map<std::string, std::string> text;        // optional (empty map = absent)
  std::map<std::string, Segment> segments;        // optional
  std::map<std::string, double> reco2dur;         // optional
  std::map<std::string, std::string> utt2uniq;    // optional

  bool has_segments() const { return !segments.empty(); }
  // spk -> sorted utterance list, derived from utt2spk.
  std::map<std::string, std::vector<std::string>> spk2utt() const;
  // Utterance ids (= recording ids without segments).
  std::vector<std::string> utterances() const;
};

// Reads `dir`; errors name the file and line. Also cross-checks spk2utt against utt2spk if present.
DataDir read_data_dir(const std::string& dir);

// Returns a list of problems (empty = valid): the checks of validate_data_dir.sh --no-feats
// (sorted/unique files, utt2spk/spk2utt agreement, segments 4 fields with end > start and known
// recordings, text and utt2uniq covering the utterances, no '~' in wav.scp...).
std::vector<std::string> validate_data_dir(const std::string& dir, bool require_text = false);

// Writes every present table plus a regenerated spk2utt, sorted, into `dir` (which must exist).
void write_data_dir(const std::string& dir, const DataDir& data);

}  // namespace tsrir
