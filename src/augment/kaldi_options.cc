#include "augment/kaldi_options.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "util/cli.h"
#include "util/error.h"
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
  add_entry("config", Kind::kString, &config_,
            "Configuration file to read (this option may be repeated)", "", true);
  add_entry("help", Kind::kBool, &help_, "Print out usage message", "false", true);
  add_entry("print-args", Kind::kBool, &print_args_, "Print the command line arguments (to stderr)",
            "true", true);
  add_entry("verbose", Kind::kInt, &verbose_, "Verbose level (higher->more logging)", "0", true);
}

void KaldiOptionParser::add_entry(const std::string& name, Kind kind, void* target,
                                  const std::string& help, const std::string& default_text,
                                  bool standard) {
  std::string key = normalize_name(name);
  if (entries_.count(key)) throw Error("option registered twice: --" + name);
  entries_[key] = Entry{name, kind, target, help, default_text, standard};
}

void KaldiOptionParser::add(const std::string& name, bool* value, const std::string& help) {
  add_entry(name, Kind::kBool, value, help, *value ? "true" : "false", false);
}
void KaldiOptionParser::add(const std::string& name, int* value, const std::string& help) {
  add_entry(name, Kind::kInt, value, help, std::to_string(*value), false);
}
void KaldiOptionParser::add(const std::string& name, float* value, const std::string& help) {
  add_entry(name, Kind::kFloat, value, help, format_double(*value), false);
}
void KaldiOptionParser::add(const std::string& name, double* value, const std::string& help) {
  add_entry(name, Kind::kDouble, value, help, format_double(*value), false);
}
void KaldiOptionParser::add(const std::string& name, std::string* value, const std::string& help) {
  add_entry(name, Kind::kString, value, help, *value, false);
}

void KaldiOptionParser::set_option(const std::string& key, const std::string& value,
                                   bool has_equal_sign, const std::string& original) {
  auto it = entries_.find(key);
  if (it == entries_.end()) throw Error("Invalid option " + original);
  const Entry& e = it->second;
  switch (e.kind) {
    case Kind::kBool:
      if (has_equal_sign && value.empty()) throw Error("Invalid option --" + key + "=");
      *static_cast<bool*>(e.target) = to_bool(value, original);
      break;
    case Kind::kInt: {
      if (!has_equal_sign) throw Error("Invalid option " + original + " (option format is --x=y)");
      *static_cast<int*>(e.target) = static_cast<int>(parse_int(value, "option --" + key));
      break;
    }
    case Kind::kFloat:
      if (!has_equal_sign) throw Error("Invalid option " + original + " (option format is --x=y)");
      *static_cast<float*>(e.target) = static_cast<float>(parse_double(value, "option --" + key));
      break;
    case Kind::kDouble:
      if (!has_equal_sign) throw Error("Invalid option " + original + " (option format is --x=y)");
      *static_cast<double*>(e.target) = parse_double(value, "option --" + key);
      break;
    case Kind::kString:
      if (!has_equal_sign) throw Error("Invalid option " + original + " (option format is --x=y)");
      *static_cast<std::string*>(e.target) = value;
      break;
  }
}

void KaldiOptionParser::read_config_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("Cannot open config file: " + path);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    line = trim(line);
    if (line.empty()) continue;
    if (!starts_with(line, "--"))
      throw Error(located(path, line_number, "does not look like a line from a Kaldi config file: should be of the form --x=y"));
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
  bool header = false;
  for (const auto& [key, e] : entries_) {
    if (e.standard) continue;
    if (!header) out << "Options:\n";
    header = true;
    out << "  --" << std::setw(25) << std::left << e.name << " : " << e.help << " (default: "
        << (e.kind == Kind::kString ? "'" + e.default_text + "'" : e.default_text) << ")\n";
  }
  if (header) out << '\n';
  out << "Standard options:\n";
  for (const auto& [key, e] : entries_) {
    if (!e.standard) continue;
    out << "  --" << std::setw(25) << std::left << e.name << " : " << e.help << '\n';
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
  bool finished = false;  // false after an exception: the status is then run_program's error code
  const int status = run_program(name, [&]() {
    KaldiOptionParser po(usage);
    define(po);
    if (po.parse(argc, argv) == KaldiOptionParser::Outcome::kHelp) {
      std::cout << po.usage_text();
      finished = true;
      return 0;
    }
    if (po.positionals().size() != num_positionals) {
      std::cerr << po.usage_text();
      finished = true;
      return 1;
    }
    const int rc = body(po.positionals());
    finished = true;
    return rc;
  });
  return status != 0 && !finished ? 255 : status;
}

}  // namespace tsrir
