#include "util/cli.h"

#include <boost/program_options.hpp>
#include <cctype>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>

#include "util/config_file.h"
#include "util/error.h"

namespace po = boost::program_options;

namespace tsrir {
namespace {

const char kPositional[] = "positional-arguments__";

// Boost.Program_options lays out --help and tokenises the command line; values are kept as text
// and converted by the OptionSpec setters, in command-line order, after the config files.
void describe(po::options_description* desc, const std::string& name, const OptionSpec& spec,
              const std::string& help) {
  auto* value = po::value<std::string>();
  if (!spec.repeated) value->default_value(spec.default_text, spec.default_text);
  if (spec.is_flag) value->implicit_value("true", "true");
  desc->add_options()(name.c_str(), value, help.c_str());
}

}  // namespace

CommandLine::CommandLine(std::string program, std::string usage)
    : program_(std::move(program)), usage_(std::move(usage)) {}

CommandLine::~CommandLine() = default;

void CommandLine::RegisterSpec(OptionSpec spec) {
  if (spec.name.empty() || spec.name == "help" || spec.name == "config" || index_.count(spec.name)) {
    throw Error("option --" + spec.name + " registered twice or reserved (a program bug)");
  }
  index_[spec.name] = specs_.size();
  specs_.push_back(std::move(spec));
}

void CommandLine::RegisterAlias(const std::string& alias, const std::string& name) {
  auto it = index_.find(name);
  if (it == index_.end() || alias == "help" || alias == "config" || index_.count(alias)) {
    throw Error("alias --" + alias + " of --" + name + ": unknown option or name taken (a program bug)");
  }
  index_[alias] = it->second;
  aliases_.emplace_back(alias, name);
}

const OptionSpec* CommandLine::find(const std::string& name) const {
  auto it = index_.find(name);
  return it == index_.end() ? nullptr : &specs_[it->second];
}

std::string CommandLine::hint() const { return "Try '" + program_ + " --help'."; }

std::string CommandLine::usage_text() const {
  po::options_description desc("Options");
  desc.add_options()("help,h", "Print this usage message and exit");
  desc.add_options()("config", po::value<std::string>()->value_name("FILE"),
                     "Read options from FILE, one --name=value per line ('#' starts a comment); "
                     "options on the command line override it");
  for (const auto& spec : specs_) {
    describe(&desc, spec.name, spec, spec.help);
    for (const auto& [alias, name] : aliases_) {
      if (name == spec.name) describe(&desc, alias, spec, "same as --" + spec.name);
    }
  }
  std::ostringstream os;
  os << usage_;
  if (!usage_.empty() && usage_.back() != '\n') os << '\n';
  os << '\n' << desc;
  return os.str();
}

void CommandLine::apply(const OptionSpec& spec, const std::string& value, bool has_value, const std::string& where) {
  std::string text = value;
  if (!has_value) {
    if (!spec.is_flag) throw Error(where + "option --" + spec.name + " needs a value (--" + spec.name + "=VALUE)");
    text = "true";
  }
  try {
    spec.set(text);
  } catch (const Error& e) {
    throw Error(where + "invalid value '" + text + "' for --" + spec.name + ": " + e.what());
  }
}

std::vector<std::string> CommandLine::parse(int argc, const char* const* argv, int min_positional,
                                            int max_positional) {
  po::options_description desc;
  desc.add_options()("help,h", "");
  desc.add_options()("config", po::value<std::string>(), "");
  for (const auto& [name, i] : index_) describe(&desc, name, specs_[i], "");
  desc.add_options()(kPositional, po::value<std::vector<std::string>>());
  po::positional_options_description pos;
  pos.add(kPositional, -1);

  // A bare boolean "--flag" must not swallow the next word as its value.
  // "--name=" (an empty value, as Kaldi allows) goes to Boost as "--name" "".
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
      const OptionSpec* spec = find(a.substr(2));
      if (spec && spec->is_flag && separate_boolean_values_ && i + 1 < argc) {
        std::string next = argv[i + 1];
        for (char& c : next) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (next == "true" || next == "false") {
          args.push_back(a + "=" + next);
          ++i;
          continue;
        }
      }
      if (spec && spec->is_flag) a += "=true";
      const OptionSpec* empty_valued = a.size() > 3 && a.find('=') == a.size() - 1 ? find(a.substr(2, a.size() - 3)) : nullptr;
      if (empty_valued && !empty_valued->is_flag) {
        args.push_back(a.substr(0, a.size() - 1));
        args.emplace_back();
        continue;
      }
    }
    args.push_back(std::move(a));
  }

  struct Item {
    const OptionSpec* spec;
    std::string value;
    bool has_value;
  };
  std::vector<Item> command_line;
  std::vector<std::string> config_files, positional;
  try {
    const auto style = po::command_line_style::default_style & ~po::command_line_style::allow_guessing;
    const po::parsed_options parsed = po::command_line_parser(args).options(desc).positional(pos).style(style).run();
    for (const po::option& o : parsed.options) {
      if (o.string_key == "help") {
        std::cout << usage_text();
        std::exit(0);
      }
      if (o.string_key == kPositional) {
        positional.insert(positional.end(), o.value.begin(), o.value.end());
      } else if (o.string_key == "config") {
        config_files.push_back(o.value.empty() ? "" : o.value.front());
      } else {
        const OptionSpec* spec = find(o.string_key);
        if (!spec) throw Error("unknown option '--" + o.string_key + "'");
        command_line.push_back({spec, o.value.empty() ? "" : o.value.front(), !o.value.empty()});
      }
    }
  } catch (const po::error& e) {
    throw Error(std::string(e.what()) + "\n" + hint());
  }

  // A repeated option's values come from one place: the first occurrence on the command line (or in
  // the config files) replaces the default list and anything the config files gave.
  std::set<const OptionSpec*> cleared;
  auto set_one = [&](const OptionSpec& spec, const std::string& value, bool has_value, const std::string& where) {
    if (spec.repeated && cleared.insert(&spec).second) spec.clear();
    apply(spec, value, has_value, where);
  };
  for (const std::string& file : config_files) {
    for (const ConfigEntry& e : read_config_file(file)) {
      const std::string where = located(file, e.line, "");
      if (e.name == "config") throw Error(where + "--config cannot be nested in a config file");
      const OptionSpec* spec = find(e.name);
      if (!spec) throw Error(where + "unknown option '--" + e.name + "'\n" + hint());
      try {
        set_one(*spec, e.value, e.has_value, where);
      } catch (const Error& err) {
        throw Error(std::string(err.what()) + "\n" + hint());
      }
    }
  }
  cleared.clear();
  for (const Item& item : command_line) {
    try {
      set_one(*item.spec, item.value, item.has_value, "");
    } catch (const Error& err) {
      throw Error(std::string(err.what()) + "\n" + hint());
    }
  }

  const int n = static_cast<int>(positional.size());
  if (n < min_positional || (max_positional >= 0 && n > max_positional)) {
    throw Error("wrong number of arguments (" + std::to_string(n) + "; expected " +
                (max_positional == min_positional ? std::to_string(min_positional)
                 : max_positional < 0             ? "at least " + std::to_string(min_positional)
                                                  : std::to_string(min_positional) + " to " + std::to_string(max_positional)) +
                ")\n" + hint());
  }
  return positional;
}

}  // namespace tsrir
