#include "util/settings_file.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

const char kFormatKey[] = "format";

std::string key_of(const std::string& name, const SettingsStyle& style) {
  std::string key = name;
  if (style.underscores) std::replace(key.begin(), key.end(), '-', '_');
  return key;
}

// A value a line can hold and give back unchanged.
void check_storable(const std::string& key, const std::string& value) {
  if (value.find('\n') != std::string::npos || value.find('\r') != std::string::npos || trim(value) != value) {
    throw Error("setting '" + key + "': the value '" + value +
                "' has a line break or surrounding spaces, which a settings line cannot hold");
  }
}

}  // namespace

SettingsFile::SettingsFile(std::string format_tag, std::string what, SettingsStyle style)
    : format_tag_(std::move(format_tag)), what_(std::move(what)), style_(style) {
  Setting format;
  format.key = kFormatKey;
  format.spec.name = kFormatKey;
  const std::string tag = format_tag_;
  format.spec.get = [tag](int) { return std::vector<std::string>{tag}; };
  format.spec.set = [tag](const std::string& text) {
    if (text != tag) throw Error("the format is '" + text + "', not " + tag);
  };
  settings_.push_back(std::move(format));
}

void SettingsFile::RegisterSpec(OptionSpec spec) {
  Setting s;
  s.key = key_of(spec.name, style_);
  if (find(s.key)) throw Error("setting '" + s.key + "' registered twice (a program bug)");
  s.spec = std::move(spec);
  settings_.push_back(std::move(s));
}

// A file names each setting once, by its own name.
void SettingsFile::RegisterAlias(const std::string&, const std::string&) {}

void SettingsFile::Exclude(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    auto it = std::find_if(settings_.begin(), settings_.end(), [&](const Setting& s) { return s.spec.name == name; });
    if (it == settings_.end()) throw Error("settings: no option '" + name + "' to exclude (a program bug)");
    settings_.erase(it);
  }
}

void SettingsFile::Rename(const std::string& name, const std::string& key) {
  for (Setting& s : settings_) {
    if (s.spec.name != name) continue;
    if (find(key)) throw Error("settings: key '" + key + "' taken (a program bug)");
    s.key = key;
    return;
  }
  throw Error("settings: no option '" + name + "' to rename (a program bug)");
}

void SettingsFile::OmitWhenDefault(const std::vector<std::string>& names, const SettingsValues& defaults) {
  for (const std::string& name : names) {
    auto it = std::find_if(settings_.begin(), settings_.end(), [&](const Setting& s) { return s.spec.name == name; });
    if (it == settings_.end() || it->spec.repeated || !it->spec.get) {
      throw Error("settings: no single-valued option '" + name + "' to omit when default (a program bug)");
    }
    const auto value = defaults.find(it->key);
    if (value == defaults.end()) throw Error("settings: no default given for '" + name + "' (a program bug)");
    it->omit_when_default = true;
    it->default_value = value->second;
  }
}

void SettingsFile::Order(const std::vector<std::string>& keys) { order_ = keys; }

const SettingsFile::Setting* SettingsFile::find(const std::string& key) const {
  for (const Setting& s : settings_) {
    if (s.key == key) return &s;
  }
  return nullptr;
}

std::vector<const SettingsFile::Setting*> SettingsFile::in_file_order() const {
  std::vector<const Setting*> out;
  for (const Setting& s : settings_) out.push_back(&s);
  if (style_.sorted) {
    std::sort(out.begin(), out.end(), [](const Setting* a, const Setting* b) { return a->key < b->key; });
    return out;
  }
  auto rank = [this](const Setting* s) {
    if (s->key == kFormatKey) return -1L;
    const auto it = std::find(order_.begin(), order_.end(), s->key);
    return it == order_.end() ? long(order_.size()) : long(it - order_.begin());
  };
  std::stable_sort(out.begin(), out.end(), [&](const Setting* a, const Setting* b) { return rank(a) < rank(b); });
  return out;
}

SettingsValues SettingsFile::values() const {
  SettingsValues out;
  for (const Setting& s : settings_) {
    if (!s.spec.get) throw Error("setting '" + s.key + "' cannot be written to a settings file (a program bug)");
    const std::vector<std::string> texts = s.spec.get(style_.double_digits);
    if (!s.spec.repeated && texts.size() != 1) throw Error("setting '" + s.key + "' has no value to write");
    std::string joined;
    for (size_t i = 0; i < texts.size(); ++i) {
      check_storable(s.key, texts[i]);
      joined += (i ? "\n" : "") + texts[i];
    }
    if (s.omit_when_default && joined == s.default_value) continue;
    out[s.key] = joined;
  }
  return out;
}

std::string SettingsFile::text() const {
  const SettingsValues v = values();
  std::ostringstream os;
  for (const Setting* s : in_file_order()) {
    if (!v.count(s->key)) continue;  // omitted when default
    const std::string& joined = v.at(s->key);
    if (s->spec.repeated && joined.empty()) continue;
    for (const std::string& value : split(joined, '\n')) os << s->key << ' ' << value << '\n';
  }
  return os.str();
}

std::vector<SettingsFile::Line> SettingsFile::lines(const std::string& text, const std::string& where) const {
  std::vector<Line> out;
  std::set<std::string> seen;
  std::istringstream in(text);
  std::string raw;
  int line_no = 0;
  bool have_format = false;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string t = trim(raw);
    if (t.empty() || t[0] == '#') continue;
    const size_t space = t.find_first_of(" \t");
    Line line{t.substr(0, space), space == std::string::npos ? "" : trim(t.substr(space)), line_no};
    const Setting* s = find(line.key);
    if (!s) throw Error(located(where, line_no, "unknown setting '" + line.key + "' (" + what_ + ")"));
    if (!seen.insert(line.key).second && !s->spec.repeated) {
      throw Error(located(where, line_no, "'" + line.key + "' given twice"));
    }
    if (line.key == kFormatKey) {
      if (line.value != format_tag_) {
        throw Error(located(where, line_no, "format '" + line.value + "', not " + format_tag_ + " (" + what_ + ")"));
      }
      have_format = true;
    }
    out.push_back(std::move(line));
  }
  if (!have_format) {
    throw Error(where + ": not " + what_ + " (no '" + std::string(kFormatKey) + " " + format_tag_ + "' line)");
  }
  return out;
}

SettingsValues SettingsFile::read(const std::string& text, const std::string& where) const {
  SettingsValues out;
  for (const Line& line : lines(text, where)) {
    auto [it, fresh] = out.emplace(line.key, line.value);
    if (!fresh) it->second += "\n" + line.value;
  }
  return out;
}

void SettingsFile::set_value(const Setting& s, const std::string& value, const std::string& where) const {
  try {
    s.spec.set(value);
  } catch (const Error& e) {
    throw Error(where + ": invalid value '" + value + "' for '" + s.key + "': " + e.what());
  }
}

void SettingsFile::check_complete(const std::set<std::string>& present, const std::string& where) const {
  for (const Setting& s : settings_) {
    if (present.count(s.key)) continue;
    if (s.omit_when_default) {
      set_value(s, s.default_value, where);
      continue;
    }
    if (s.spec.repeated && s.spec.clear && style_.require_all) s.spec.clear();  // none stored: none
    if (!s.spec.repeated && style_.require_all) throw Error(where + ": settings lack '" + s.key + "'");
  }
}

void SettingsFile::apply(const SettingsValues& values, const std::string& where) {
  std::set<std::string> present;
  for (const auto& [key, value] : values) {
    const Setting* s = find(key);
    if (!s) throw Error(where + ": unknown setting '" + key + "' (" + what_ + ")");
    if (s->spec.repeated && s->spec.clear) s->spec.clear();
    for (const std::string& one : s->spec.repeated ? split(value, '\n') : std::vector<std::string>{value}) {
      set_value(*s, one, where);
    }
    present.insert(key);
  }
  check_complete(present, where);
}

void SettingsFile::parse(const std::string& text, const std::string& where) {
  std::set<std::string> present;
  for (const Line& line : lines(text, where)) {
    const Setting& s = *find(line.key);
    // A repeated option's first line replaces the values it had.
    if (present.insert(line.key).second && s.spec.repeated && s.spec.clear) s.spec.clear();
    const std::string at = where + ":" + std::to_string(line.line);
    set_value(s, line.value, at);
  }
  check_complete(present, where);
}

std::string settings_difference(const SettingsValues& stored, const SettingsValues& asked) {
  std::string diff;
  for (const auto& [k, v] : stored) {
    auto it = asked.find(k);
    if (it == asked.end() || it->second != v) diff += " --" + k + "=" + v;
  }
  return diff;
}

std::string read_settings_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  std::ostringstream os;
  os << in.rdbuf();
  if (in.bad()) throw Error(path + ": read error");
  return os.str();
}

}  // namespace tsrir
