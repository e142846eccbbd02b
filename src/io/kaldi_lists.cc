#include "io/kaldi_lists.h"

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "io/shell.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

std::vector<std::string> shlex_split(const std::string& line, const std::string& context) {
  std::vector<std::string> out;
  std::string cur;
  bool in_word = false;
  for (size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (c == '\'') {
      size_t j = line.find('\'', i + 1);
      if (j == std::string::npos) throw Error(context + ": unterminated single quote");
      cur += line.substr(i + 1, j - i - 1);
      in_word = true;
      i = j;
    } else if (c == '"') {
      in_word = true;
      size_t j = i + 1;
      for (; j < line.size() && line[j] != '"'; ++j) {
        if (line[j] == '\\' && j + 1 < line.size() &&
            (line[j + 1] == '"' || line[j + 1] == '\\' || line[j + 1] == '$' || line[j + 1] == '`')) {
          ++j;
        }
        cur += line[j];
      }
      if (j >= line.size()) throw Error(context + ": unterminated double quote");
      i = j;
    } else if (c == '\\') {
      if (i + 1 >= line.size()) throw Error(context + ": trailing backslash");
      cur += line[++i];
      in_word = true;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      if (in_word) out.push_back(cur);
      cur.clear();
      in_word = false;
    } else {
      cur += c;
      in_word = true;
    }
  }
  if (in_word) out.push_back(cur);
  return out;
}

namespace {

// argparse-like: "--name value" or "--name=value"; the remaining non-option word is the rxfilename.
// Pipe commands arrive as several words ending in "|"; they are joined back with spaces.
struct ParsedLine {
  std::map<std::string, std::string> options;
  std::string rxfilename;
};

// A NUL or other control byte would be cut off or reinterpreted by the C file APIs ("a.wav\0x"
// opens "a.wav"): refused, as in tables.
void check_no_control_characters(const std::string& line, const std::string& context) {
  for (unsigned char c : line) {
    if (c < 0x20 && c != '\t') throw Error(context + ": control character in line");
  }
}

ParsedLine parse_option_line(const std::string& line, const std::set<std::string>& known,
                             const std::string& context) {
  check_no_control_characters(line, context);
  ParsedLine p;
  auto words = shlex_split(line, context);
  std::vector<std::string> rest;
  for (size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (starts_with(w, "--") && rest.empty()) {
      std::string name = w.substr(2), value;
      size_t eq = name.find('=');
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
      } else {
        if (i + 1 >= words.size()) throw Error(context + ": option --" + name + " needs a value");
        value = words[++i];
      }
      if (!known.count(name)) throw Error(context + ": unknown option --" + name);
      if (p.options.count(name)) throw Error(context + ": option --" + name + " given twice");
      p.options[name] = value;
    } else {
      rest.push_back(w);
    }
  }
  if (rest.empty()) throw Error(context + ": no file name (rxfilename) at the end of the line");
  if (rest.size() > 1 && rest.back() != "|" && !ends_with(rest.back(), "|")) {
    throw Error(context + ": more than one file name: '" + rest[0] + "' and '" + rest[1] + "'");
  }
  for (size_t i = 0; i < rest.size(); ++i) p.rxfilename += (i ? " " : "") + rest[i];
  if (trim(p.rxfilename).empty()) throw Error(context + ": empty file name (rxfilename)");
  return p;
}

std::optional<double> opt_double(const ParsedLine& p, const std::string& name, const std::string& context) {
  auto it = p.options.find(name);
  if (it == p.options.end()) return std::nullopt;
  return parse_double(it->second, context + ": --" + name);
}

std::string required(const ParsedLine& p, const std::string& name, const std::string& context) {
  auto it = p.options.find(name);
  if (it == p.options.end() || it->second.empty()) throw Error(context + ": missing --" + name);
  return it->second;
}

std::string optional_str(const ParsedLine& p, const std::string& name) {
  auto it = p.options.find(name);
  return it == p.options.end() ? "" : it->second;
}

void check_probability(const std::optional<double>& p, const std::string& context) {
  if (p && (*p < 0.0 || *p > 1.0)) throw Error(context + ": --probability must be in [0, 1]");
}

std::vector<std::pair<int, std::string>> read_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  std::vector<std::pair<int, std::string>> lines;
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    std::string t = trim(line);
    if (t.empty()) continue;
    check_no_control_characters(t, path + ":" + std::to_string(n));
    lines.emplace_back(n, t);
  }
  return lines;
}

bool looks_like_option_list(const std::vector<std::pair<int, std::string>>& lines) {
  return !lines.empty() && starts_with(lines.front().second, "--");
}

}  // namespace

RirListEntry parse_rir_list_line(const std::string& line, const std::string& context) {
  static const std::set<std::string> known = {"rir-id", "room-id", "receiver-position-id", "source-position-id",
                                              "rt60", "drr", "cte", "probability"};
  ParsedLine p = parse_option_line(line, known, context);
  RirListEntry e;
  e.rir_id = required(p, "rir-id", context);
  e.room_id = required(p, "room-id", context);
  e.receiver_position_id = optional_str(p, "receiver-position-id");
  e.source_position_id = optional_str(p, "source-position-id");
  e.rt60 = opt_double(p, "rt60", context);
  e.drr = opt_double(p, "drr", context);
  e.cte = opt_double(p, "cte", context);
  e.probability = opt_double(p, "probability", context);
  check_probability(e.probability, context);
  e.rxfilename = p.rxfilename;
  return e;
}

const Choices<BgFgType>& bg_fg_type_choices() {
  static const Choices<BgFgType> choices = {{"background", BgFgType::kBackground},
                                            {"foreground", BgFgType::kForeground}};
  return choices;
}

NoiseListEntry parse_noise_list_line(const std::string& line, const std::string& context) {
  static const std::set<std::string> known = {"noise-id", "noise-type", "bg-fg-type", "room-linkage", "probability"};
  ParsedLine p = parse_option_line(line, known, context);
  NoiseListEntry e;
  e.noise_id = required(p, "noise-id", context);
  e.noise_type = required(p, "noise-type", context);
  if (e.noise_type != "isotropic" && e.noise_type != "point-source") {
    throw Error(context + ": --noise-type must be isotropic or point-source, got '" + e.noise_type + "'");
  }
  if (p.options.count("bg-fg-type")) {
    const std::string& type = p.options.at("bg-fg-type");
    try {
      e.bg_fg_type = choice_value(bg_fg_type_choices(), type);
    } catch (const Error&) {
      throw Error(context + ": --bg-fg-type must be background or foreground, got '" + type + "'");
    }
  }
  e.room_linkage = optional_str(p, "room-linkage");
  if (e.noise_type == "isotropic" && e.room_linkage.empty()) {
    throw Error(context + ": isotropic noise needs --room-linkage");
  }
  e.probability = opt_double(p, "probability", context);
  check_probability(e.probability, context);
  e.rxfilename = p.rxfilename;
  return e;
}

// Kaldi's reverberate_data_dir.py hands every line of a list to argparse: a "#" line is not a
// comment there but a malformed entry that stops the script. Refused here too, with the reason.
static void refuse_comment_lines(const std::vector<std::pair<int, std::string>>& lines, const std::string& path,
                          const std::string& kind) {
  for (const auto& [n, text] : lines) {
    if (!text.empty() && text[0] == '#')
      throw Error(path + ":" + std::to_string(n) + ": a " + kind +
                  " list has no comment lines (Kaldi's reverberate_data_dir.py fails on this line too); "
                  "remove the line");
  }
}

std::vector<RirListEntry> read_rir_list(const std::string& path) {
  auto lines = read_lines(path);
  if (lines.empty()) throw Error(path + ": empty RIR list");
  refuse_comment_lines(lines, path, "RIR");
  const bool option_form = looks_like_option_list(lines);
  std::vector<RirListEntry> out;
  std::map<std::string, int> seen;
  for (const auto& [n, text] : lines) {
    const std::string context = path + ":" + std::to_string(n);
    RirListEntry e;
    if (option_form) {
      e = parse_rir_list_line(text, context);
    } else {
      size_t sp = text.find_first_of(" \t");
      if (sp == std::string::npos) throw Error(context + ": expected '<rir-id> <rxfilename>'");
      e.rir_id = text.substr(0, sp);
      e.room_id = e.rir_id;
      e.rxfilename = trim(text.substr(sp));
    }
    e.line = n;
    auto [it, inserted] = seen.emplace(e.rir_id, n);
    if (!inserted) {
      throw Error(context + ": duplicate RIR id '" + e.rir_id + "' (first at line " + std::to_string(it->second) + ")");
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<NoiseListEntry> read_noise_list(const std::string& path) {
  auto lines = read_lines(path);
  // An empty noise list is no error: Kaldi's script then adds no noise from it.
  if (lines.empty()) return {};
  refuse_comment_lines(lines, path, "noise");
  const bool option_form = looks_like_option_list(lines);
  std::vector<NoiseListEntry> out;
  std::map<std::string, int> seen;
  for (const auto& [n, text] : lines) {
    const std::string context = path + ":" + std::to_string(n);
    NoiseListEntry e;
    if (option_form) {
      e = parse_noise_list_line(text, context);
    } else {
      size_t sp = text.find_first_of(" \t");
      if (sp == std::string::npos) throw Error(context + ": expected '<noise-id> <rxfilename>'");
      e.noise_id = text.substr(0, sp);
      e.noise_type = "point-source";
      e.rxfilename = trim(text.substr(sp));
    }
    e.line = n;
    auto [it, inserted] = seen.emplace(e.noise_id, n);
    if (!inserted) {
      throw Error(context + ": duplicate noise id '" + e.noise_id + "' (first at line " + std::to_string(it->second) + ")");
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::string format_rir_list_line(const RirListEntry& e) {
  std::ostringstream os;
  os << "--rir-id " << shell_quote(e.rir_id) << " --room-id " << shell_quote(e.room_id);
  if (!e.receiver_position_id.empty()) os << " --receiver-position-id " << shell_quote(e.receiver_position_id);
  if (!e.source_position_id.empty()) os << " --source-position-id " << shell_quote(e.source_position_id);
  if (e.rt60) os << " --rt60 " << format_double(*e.rt60);
  if (e.drr) os << " --drr " << format_double(*e.drr);
  if (e.cte) os << " --cte " << format_double(*e.cte);
  if (e.probability) os << " --probability " << format_double(*e.probability);
  // Quoted as one word, pipes too (Kaldi's own form: "sox x.wav -t wav - |"): written bare, a pipe
  // would be re-split by shlex on reading and lose its own quoting ('my file.wav' -> my file.wav).
  os << ' ' << shell_quote(e.rxfilename);
  return os.str();
}

}  // namespace tsrir
