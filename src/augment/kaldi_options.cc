#include "augment/kaldi_options.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "util/commented_lines.h"
#include "util/error.h"
#include "util/program.h"
#include "util/strings.h"

namespace tsrir {
namespace {

std::string normalize_name(const std::string& name) {
  std::string out;
  for (char c : name) out += (c == '_') ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// --key=value / --key (has_equal_sign false). An empty key ("--=x") is an error, as in Kaldi.
void split_long_arg(const std::string& arg, std::string* key, std::string* value, bool* has_equal_sign) {
  size_t pos = arg.find('=');
  if (pos == std::string::npos) {
    *key = arg.substr(2);
    value->clear();
    *has_equal_sign = false;
  } else if (pos == 2) {
    throw Error("Invalid option (no key): " + arg);
  } else {
    *key = arg.substr(2, pos - 2);
    *value = arg.substr(pos + 1);
    *has_equal_sign = true;
  }
}

bool to_bool(std::string text, const std::string& original) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (text == "true" || text == "t" || text == "1" || text.empty()) return true;
  if (text == "false" || text == "f" || text == "0") return false;
  throw Error("Invalid format for boolean argument [expected true or false]: " + original);
}

}  // namespace

KaldiOptionParser::KaldiOptionParser(std::string usage) : usage_(std::move(usage)) {
  // The standard options, as Kaldi's ParseOptions registers them; not library options.
  auto standard = [this](const std::string& name, const std::string& help, const std::string& default_text,
                         bool is_flag, std::function<void(const std::string&)> set) {
    OptionSpec spec;
    spec.name = name;
    spec.help = help;
    spec.default_text = default_text;
    spec.is_flag = is_flag;
    spec.set = std::move(set);
    add_entry(std::move(spec), true);
  };
  standard("config", "Configuration file to read (this option may be repeated)", "", false,
           [this](const std::string& v) { config_ = v; });
  standard("help", "Print out usage message", "false", true, [this](const std::string& v) { help_ = v == "true"; });
  standard("print-args", "Print the command line arguments (to stderr)", "true", true,
           [this](const std::string& v) { print_args_ = v == "true"; });
  standard("verbose", "Verbose level (higher->more logging)", "0", false,
           [this](const std::string& v) { verbose_ = static_cast<int>(parse_int(v, "option --verbose")); });
}

void KaldiOptionParser::add_entry(OptionSpec spec, bool standard) {
  const std::string key = normalize_name(spec.name);
  if (key.empty() || index_.count(key)) throw Error("option --" + spec.name + " registered twice (a program bug)");
  index_[key] = entries_.size();
  Entry e;
  e.spec = std::move(spec);
  e.standard = standard;
  entries_.push_back(std::move(e));
}

void KaldiOptionParser::RegisterSpec(OptionSpec spec) { add_entry(std::move(spec), false); }

void KaldiOptionParser::RegisterAlias(const std::string& alias, const std::string& name) {
  const std::string key = normalize_name(alias);
  auto it = index_.find(normalize_name(name));
  if (it == index_.end() || index_.count(key))
    throw Error("alias --" + alias + " of --" + name + ": unknown option or name taken (a program bug)");
  index_[key] = it->second;
  entries_[it->second].aliases.push_back(alias);
}

KaldiOptionParser::Entry* KaldiOptionParser::find(const std::string& normalized_key) {
  auto it = index_.find(normalized_key);
  return it == index_.end() ? nullptr : &entries_[it->second];
}

void KaldiOptionParser::set_option(const std::string& key, const std::string& value,
                                   bool has_equal_sign, const std::string& original) {
  Entry* e = find(key);
  if (!e) throw Error("Invalid option " + original);
  const OptionSpec& spec = e->spec;
  std::string text = value;
  if (spec.is_flag) {
    // Kaldi's booleans: --x, --x=true|t|1, --x=false|f|0 (any case); "--x=" is an error.
    if (has_equal_sign && value.empty()) throw Error("Invalid option --" + key + "=");
    text = to_bool(value, original) ? "true" : "false";
  } else if (!has_equal_sign) {
    throw Error("Invalid option " + original + " (option format is --x=y)");
  }
  if (spec.repeated && spec.clear && !e->cleared) {
    spec.clear();
    e->cleared = true;
  }
  try {
    spec.set(text);
  } catch (const Error& err) {
    throw Error("Invalid option " + original + ": " + err.what());
  }
  e->given = true;
}

bool KaldiOptionParser::given(const std::string& name) const {
  auto it = index_.find(normalize_name(name));
  return it != index_.end() && entries_[it->second].given;
}

void KaldiOptionParser::read_config_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("Cannot open config file: " + path);
  CommentedLines lines(in);
  std::string line;
  while (lines.next(&line)) {
    if (!starts_with(line, "--"))
      throw Error(located(path, lines.lines_read(), "does not look like a line from a Kaldi config file: should be of the form --x=y"));
    std::string key, value;
    bool has_equal_sign = false;
    split_long_arg(line, &key, &value, &has_equal_sign);
    key = normalize_name(key);
    if (key == "config") continue;  // nested configs are not followed, as in Kaldi
    set_option(key, trim(value), has_equal_sign, line + " in config file " + path);
  }
}

KaldiOptionParser::Outcome KaldiOptionParser::parse(int argc, const char* const* argv) {
  positionals_.clear();
  // First pass, as Kaldi: --config files are read before the command line (which overrides them),
  // and --help anywhere among the options wins.
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--", 2) != 0) continue;
    if (std::strcmp(argv[i], "--") == 0) break;
    std::string key, value;
    bool has_equal_sign = false;
    split_long_arg(argv[i], &key, &value, &has_equal_sign);
    key = normalize_name(key);
    if (key == "config") read_config_file(trim(value));
    if (key == "help") return Outcome::kHelp;
  }
  // A repeated option given on the command line replaces what the config files gave.
  for (Entry& e : entries_) e.cleared = false;
  int i = 1;
  bool double_dash_seen = false;
  for (; i < argc; ++i) {
    if (std::strncmp(argv[i], "--", 2) != 0) break;
    if (std::strcmp(argv[i], "--") == 0) {
      ++i;
      double_dash_seen = true;
      break;
    }
    std::string key, value;
    bool has_equal_sign = false;
    split_long_arg(argv[i], &key, &value, &has_equal_sign);
    key = normalize_name(key);
    if (key == "config") continue;  // already read
    set_option(key, trim(value), has_equal_sign, argv[i]);
  }
  for (; i < argc; ++i) {
    if (std::strcmp(argv[i], "--") == 0 && !double_dash_seen) {
      double_dash_seen = true;
    } else {
      positionals_.push_back(argv[i]);
    }
  }
  if (print_args_) {
    std::ostringstream line;
    for (int j = 0; j < argc; ++j) line << escape_for_echo(argv[j]) << ' ';
    std::cerr << line.str() << '\n';
  }
  return Outcome::kOk;
}

std::string KaldiOptionParser::usage_text() const {
  std::ostringstream out;
  out << '\n' << usage_ << '\n';
  auto line = [&out](const std::string& name, const std::string& help) {
    out << "  --" << std::setw(25) << std::left << name << " : " << help;
  };
  bool header = false;
  for (const Entry& e : entries_) {
    if (e.standard) continue;
    if (!header) out << "Options:\n";
    header = true;
    line(e.spec.name, e.spec.help);
    if (!e.spec.repeated) out << " (default: " << e.spec.default_text << ")";
    out << '\n';
    for (const std::string& alias : e.aliases) {
      line(alias, "same as --" + e.spec.name);
      out << '\n';
    }
  }
  if (header) out << '\n';
  out << "Standard options:\n";
  for (const Entry& e : entries_) {
    if (!e.standard) continue;
    line(e.spec.name, e.spec.help);
    out << '\n';
  }
  out << '\n';
  return out.str();
}

std::string KaldiOptionParser::escape_for_echo(const std::string& word) {
  static const char* kOk = "[]~#^_-+=:.,/";
  bool must_quote = word.empty();
  for (char c : word) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && !std::strchr(kOk, c)) must_quote = true;
  }
  if (!must_quote) return word;
  // Kaldi prefers double quotes when the word holds single quotes but nothing that bash
  // expands inside double quotes.
  bool use_double = word.find('\'') != std::string::npos && word.find_first_of("\"`$\\") == std::string::npos;
  char quote = use_double ? '"' : '\'';
  std::string out(1, quote);
  for (char c : word) {
    if (c == quote) out += "'\\''";
    else out += c;
  }
  out += quote;
  return out;
}

int run_kaldi_program(const std::string& name, const std::string& usage, int argc, const char* const* argv,
                      size_t num_positionals, const std::function<void(KaldiOptionParser&)>& define,
                      const std::function<int(const std::vector<std::string>&)>& body) {
  // Every error exits 1, as every tsrir program does (Kaldi's binaries exit 255; its scripts only
  // test for non-zero).
  return run_program(name, [&]() {
    KaldiOptionParser po(usage);
    define(po);
    if (po.parse(argc, argv) == KaldiOptionParser::Outcome::kHelp) {
      std::cout << po.usage_text();
      return 0;
    }
    if (po.positionals().size() != num_positionals) {
      std::cerr << po.usage_text();
      return 1;
    }
    return body(po.positionals());
  });
}

}  // namespace tsrir
