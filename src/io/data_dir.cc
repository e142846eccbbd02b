#include "io/data_dir.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "io/kaldi_table.h"
#include "util/error.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace tsrir {

std::map<std::string, std::vector<std::string>> DataDir::spk2utt() const {
  std::map<std::string, std::vector<std::string>> m;
  for (const auto& [utt, spk] : utt2spk) m[spk].push_back(utt);
  for (auto& [spk, utts] : m) std::sort(utts.begin(), utts.end(), c_locale_less);
  return m;
}

std::vector<std::string> DataDir::utterances() const {
  std::vector<std::string> out;
  for (const auto& [utt, spk] : utt2spk) out.push_back(utt);
  std::sort(out.begin(), out.end(), c_locale_less);
  return out;
}

namespace {

std::string join(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

std::map<std::string, std::string> to_map(const Table& t) {
  std::map<std::string, std::string> m;
  for (const auto& e : t.entries) m[e.key] = e.value;
  return m;
}

// Strict UTF-8 (no overlong forms, surrogates or code points above U+10FFFF): Kaldi's
// utils/validate_text.pl refuses any other text file.
bool is_utf8(const std::string& s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    size_t n = 0;
    uint32_t cp = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      n = 1, cp = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
      n = 2, cp = c & 0x0F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      n = 3, cp = c & 0x07;
    } else {
      return false;
    }
    if (i + n >= s.size()) return false;  // sequence cut off by the end of the line
    for (size_t k = 1; k <= n; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (cc & 0x3F);
    }
    if ((n == 2 && cp < 0x800) || (n == 3 && (cp < 0x10000 || cp > 0x10FFFF)) || (cp >= 0xD800 && cp <= 0xDFFF)) {
      return false;
    }
    i += n + 1;
  }
  return true;
}

}  // namespace

// One CRLF policy (docs/robustness.md): a data dir's tables with DOS line endings are an error
// wherever a program reads the data dir, as validate-data-dir reports them: Kaldi's awk/perl scripts
// keep the '\r' in the last field (speaker "spk1\r", file "a.wav\r"). RIR and noise lists are
// read as Kaldi's reverberate_data_dir.py reads them (Python's split() drops the '\r').
static void reject_dos_line_endings(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r')
      throw Error(located(path, n, "carriage return at the end of the line (DOS line endings; convert with dos2unix)"));
  }
}

DataDir read_data_dir(const std::string& dir) {
  if (!fs::is_directory(dir)) throw Error(dir + ": not a directory");
  for (const char* name : {"wav.scp", "utt2spk", "spk2utt", "text", "segments", "utt2uniq", "reco2file_and_channel"}) {
    if (fs::exists(join(dir, name))) reject_dos_line_endings(join(dir, name));
  }
  DataDir d;
  const std::string wav = join(dir, "wav.scp"), u2s = join(dir, "utt2spk");
  if (!fs::exists(wav)) throw Error(dir + ": no wav.scp");
  if (!fs::exists(u2s)) throw Error(dir + ": no utt2spk");
  Table wav_t = read_table(wav);
  for (const auto& e : wav_t.entries) {
    if (e.key.find('~') != std::string::npos || e.value.find('~') != std::string::npos) {
      // Kaldi's validator rejects '~' in wav.scp (it marks backup files).
      throw Error(located(wav, e.line, "'~' is not allowed in wav.scp"));
    }
  }
  d.wav_scp = to_map(wav_t);
  Table u2s_t = read_table(u2s);
  for (const auto& e : u2s_t.entries) {
    if (split_whitespace(e.value).size() != 1) throw Error(located(u2s, e.line, "expected '<utt> <spk>'"));
  }
  d.utt2spk = to_map(u2s_t);
  if (fs::exists(join(dir, "text"))) {
    TableReadOptions o;
    o.allow_empty_value = true;
    const Table t = read_table(join(dir, "text"), o);
    for (const auto& e : t.entries) {
      if (!is_utf8(e.key) || !is_utf8(e.value)) {
        throw Error(located(t.source, e.line, "not valid UTF-8 (Kaldi's utils/validate_text.pl requires UTF-8 text)"));
      }
    }
    d.text = to_map(t);
  }
  if (fs::exists(join(dir, "segments"))) {
    const std::string p = join(dir, "segments");
    Table t = read_table(p);
    for (const auto& e : t.entries) {
      auto f = split_whitespace(e.value);
      if (f.size() != 3) throw Error(located(p, e.line, "expected '<utt> <recording> <start> <end>'"));
      Segment s;
      s.recording_id = f[0];
      s.start_s = parse_double(f[1], located(p, e.line, "start"));
      s.end_s = parse_double(f[2], located(p, e.line, "end"));
      // Kaldi's extract-segments rejects a negative start; end -1 means "to the end".
      if (s.start_s < 0) throw Error(located(p, e.line, "segment start must not be negative"));
      if (!(s.end_s > s.start_s) && s.end_s != -1) throw Error(located(p, e.line, "segment end must be after its start"));
      if (!d.wav_scp.count(s.recording_id)) {
        throw Error(located(p, e.line, "recording '" + s.recording_id + "' is not in wav.scp"));
      }
      d.segments[e.key] = s;
    }
  }
  if (fs::exists(join(dir, "reco2dur"))) {
    const std::string p = join(dir, "reco2dur");
    Table t = read_table(p);
    for (const auto& e : t.entries) d.reco2dur[e.key] = parse_double(e.value, located(p, e.line, "duration"));
  }
  if (fs::exists(join(dir, "utt2uniq"))) d.utt2uniq = to_map(read_table(join(dir, "utt2uniq")));

  // Cross-checks, each naming the file and line of the first offender.
  const std::string u2s_name = u2s;
  for (const auto& e : u2s_t.entries) {
    if (d.has_segments()) {
      if (!d.segments.count(e.key)) throw Error(located(u2s, e.line, "utterance '" + e.key + "' is not in segments"));
    } else if (!d.wav_scp.count(e.key)) {
      throw Error(located(u2s, e.line, "utterance '" + e.key + "' is not in wav.scp"));
    }
  }
  if (!d.has_segments()) {
    for (const auto& e : wav_t.entries)
      if (!d.utt2spk.count(e.key)) throw Error(located(wav, e.line, "recording '" + e.key + "' has no utt2spk entry"));
  }
  if (fs::exists(join(dir, "spk2utt"))) {
    const std::string p = join(dir, "spk2utt");
    Table t = read_table(p);
    auto expected = d.spk2utt();
    for (const auto& e : t.entries) {
      auto utts = split_whitespace(e.value);
      std::sort(utts.begin(), utts.end(), c_locale_less);
      auto it = expected.find(e.key);
      if (it == expected.end() || it->second != utts) {
        throw Error(located(p, e.line, "spk2utt entry for '" + e.key + "' disagrees with utt2spk"));
      }
    }
    if (t.entries.size() != expected.size()) {
      // Every spk2utt line matched, so a speaker of utt2spk has none: name the first.
      std::set<std::string> listed;
      for (const auto& e : t.entries) listed.insert(e.key);
      for (const auto& e : u2s_t.entries) {
        const std::string spk = trim(e.value);
        if (!listed.count(spk)) throw Error(located(u2s, e.line, "speaker '" + spk + "' has no line in " + p));
      }
      throw Error(p + ": speakers disagree with utt2spk");
    }
  }
  return d;
}

std::vector<std::string> validate_data_dir(const std::string& dir, bool require_text) {
  std::vector<std::string> problems;
  auto check_sorted = [&](const std::string& name, bool required) {
    const std::string p = join(dir, name);
    if (!fs::exists(p)) {
      if (required) problems.push_back(p + ": missing");
      return;
    }
    std::ifstream in(p, std::ios::binary);
    std::string prev, line;
    int n = 0;
    bool cr_seen = false;
    while (std::getline(in, line)) {
      ++n;
      if (!cr_seen && !line.empty() && line.back() == '\r') {
        // Our readers strip it, but Kaldi's awk/perl scripts keep it in the last field
        // (speaker "spk1\r" in utt2spk_to_spk2utt.pl, file names ending in '\r'): named once per file.
        problems.push_back(located(p, n, "carriage return at the end of the line (DOS line endings; convert with dos2unix)"));
        cr_seen = true;
      }
      std::string key = line.substr(0, line.find_first_of(" \t"));
      if (key.empty()) {
        problems.push_back(located(p, n, "empty key"));
        continue;
      }
      if (n > 1 && !c_locale_less(prev, key)) {
        problems.push_back(located(p, n, prev == key ? "duplicate key '" + key + "'" : "not sorted (LC_ALL=C)"));
      }
      prev = key;
    }
    // validate_data_dir.sh: "empty file utt2spk" (and spk2utt); likewise the other required files.
    if (n == 0 && required) problems.push_back(p + ": empty");
  };
  for (const char* f : {"wav.scp", "utt2spk", "spk2utt"}) check_sorted(f, true);
  check_sorted("text", require_text);
  for (const char* f : {"segments", "utt2uniq", "reco2dur", "reco2file_and_channel", "utt2dur"}) check_sorted(f, false);
  if (!problems.empty()) return problems;
  try {
    DataDir d = read_data_dir(dir);
    // utt2spk must also be sorted by speaker (validate_data_dir.sh: "utt2spk is not in sorted order when sorted first on speaker-id").
    std::vector<std::pair<std::string, std::string>> by_spk;
    for (const auto& [u, s] : d.utt2spk) by_spk.emplace_back(s, u);
    for (size_t i = 1; i < by_spk.size(); ++i) {
      if (c_locale_less(by_spk[i].first, by_spk[i - 1].first)) {
        problems.push_back(join(dir, "utt2spk") + ": not in sorted order when sorted on speaker id (speaker ids must be prefixes of utterance ids)");
        break;
      }
    }
    if (!fs::exists(join(dir, "spk2utt"))) problems.push_back(join(dir, "spk2utt") + ": missing");
    auto utts = d.utterances();
    if (!d.text.empty() || require_text) {
      for (const auto& u : utts)
        if (!d.text.count(u)) problems.push_back(join(dir, "text") + ": no entry for utterance '" + u + "'");
      for (const auto& [u, t] : d.text)
        if (!d.utt2spk.count(u)) problems.push_back(join(dir, "text") + ": utterance '" + u + "' not in utt2spk");
    }
    if (!d.utt2uniq.empty()) {
      for (const auto& u : utts)
        if (!d.utt2uniq.count(u)) problems.push_back(join(dir, "utt2uniq") + ": no entry for utterance '" + u + "'");
    }
    if (!d.reco2dur.empty()) {
      for (const auto& [r, v] : d.wav_scp)
        if (!d.reco2dur.count(r)) problems.push_back(join(dir, "reco2dur") + ": no entry for recording '" + r + "'");
      if (d.has_segments()) {
        // Kaldi's extract-segments drops a segment that ends more than --max-overshoot (0.5 s)
        // after its recording: the utterance would silently vanish from the features.
        const Table seg_t = read_table(join(dir, "segments"));
        for (const auto& e : seg_t.entries) {
          const Segment& sg = d.segments.at(e.key);
          auto dur = d.reco2dur.find(sg.recording_id);
          if (dur != d.reco2dur.end() && sg.end_s > dur->second + 0.5) {
            problems.push_back(located(seg_t.source, e.line, "segment ends at " + format_double(sg.end_s) + " s, after the end of recording '" +
                                                                 sg.recording_id + "' (" + format_double(dur->second) + " s in reco2dur)"));
          }
        }
      }
    }
  } catch (const Error& e) {
    problems.push_back(e.what());
  }
  return problems;
}

void write_data_dir(const std::string& dir, const DataDir& d) {
  using Rows = std::vector<std::pair<std::string, std::string>>;
  auto rows_of = [](const std::map<std::string, std::string>& m) { return Rows(m.begin(), m.end()); };
  write_table(join(dir, "wav.scp"), rows_of(d.wav_scp));
  write_table(join(dir, "utt2spk"), rows_of(d.utt2spk));
  Rows s2u;
  for (const auto& [spk, utts] : d.spk2utt()) {
    std::string v;
    for (const auto& u : utts) v += (v.empty() ? "" : " ") + u;
    s2u.emplace_back(spk, v);
  }
  write_table(join(dir, "spk2utt"), s2u);
  if (!d.text.empty()) write_table(join(dir, "text"), rows_of(d.text));
  if (!d.utt2uniq.empty()) write_table(join(dir, "utt2uniq"), rows_of(d.utt2uniq));
  if (!d.segments.empty()) {
    Rows r;
    for (const auto& [u, s] : d.segments) {
      r.emplace_back(u, s.recording_id + " " + format_double(s.start_s, 10) + " " + format_double(s.end_s, 10));
    }
    write_table(join(dir, "segments"), r);
  }
  if (!d.reco2dur.empty()) {
    Rows r;
    for (const auto& [k, v] : d.reco2dur) r.emplace_back(k, format_double(v, 10));
    write_table(join(dir, "reco2dur"), r);
  }
}

}  // namespace tsrir
