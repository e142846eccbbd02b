#include "util/options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

// The setters' errors say what was expected; CommandLine adds where the value came from.
long long to_integer(const std::string& text, long long lo, long long hi) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size()) throw Error("expected an integer");
  if (errno == ERANGE || v < lo || v > hi) {
    throw Error("out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

double to_double(const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || std::isspace(static_cast<unsigned char>(text[0]))) {
    throw Error("expected a number");
  }
  if (errno == ERANGE || !std::isfinite(v)) throw Error("number out of range");
  return v;
}

// A spec whose value is one text: its default and what a settings file stores are the same text.
template <typename T, typename Text>
OptionSpec single_valued(const std::string& name, const std::string& help, T* value, Text to_text) {
  OptionSpec spec;
  spec.name = name;
  spec.help = help;
  spec.get = [value, to_text](int digits) { return std::vector<std::string>{to_text(*value, digits)}; };
  return spec;
}

template <typename T>
void register_integer(OptionsItf* opts, const std::string& name, T* value, const std::string& help) {
  OptionSpec spec = single_valued(name, help, value, [](T v, int) { return std::to_string(v); });
  spec.default_text = std::to_string(*value);
  spec.set = [value](const std::string& text) {
    *value = static_cast<T>(to_integer(text, static_cast<long long>(std::numeric_limits<T>::min()),
                                       static_cast<long long>(std::numeric_limits<T>::max())));
  };
  opts->RegisterSpec(std::move(spec));
}

}  // namespace

void OptionsItf::Register(const std::string& name, bool* value, const std::string& help) {
  OptionSpec spec = single_valued(name, help, value, [](bool v, int) { return std::string(v ? "true" : "false"); });
  spec.default_text = *value ? "true" : "false";
  spec.is_flag = true;
  spec.set = [value](const std::string& text) {
    std::string t = text;
    for (auto& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (t == "true" || t == "1" || t == "yes" || t == "on") {
      *value = true;
    } else if (t == "false" || t == "0" || t == "no" || t == "off") {
      *value = false;
    } else {
      throw Error("expected true or false");
    }
  };
  RegisterSpec(std::move(spec));
}

void OptionsItf::Register(const std::string& name, int* value, const std::string& help) {
  register_integer(this, name, value, help);
}
void OptionsItf::Register(const std::string& name, long* value, const std::string& help) {
  register_integer(this, name, value, help);
}
void OptionsItf::Register(const std::string& name, long long* value, const std::string& help) {
  register_integer(this, name, value, help);
}
void OptionsItf::Register(const std::string& name, unsigned* value, const std::string& help) {
  register_integer(this, name, value, help);
}

void OptionsItf::Register(const std::string& name, unsigned long* value, const std::string& help) {
  static_assert(sizeof(unsigned long) == sizeof(Seed), "Seed is the 64-bit unsigned long");
  OptionSpec spec = single_valued(name, help, value, [](unsigned long v, int) { return std::to_string(v); });
  spec.default_text = std::to_string(*value);
  spec.set = [value](const std::string& text) {
    errno = 0;
    char* end = nullptr;
    if (!text.empty() && text[0] == '-') {
      const long long v = std::strtoll(text.c_str(), &end, 10);
      if (end != text.c_str() + text.size() || text.size() == 1) throw Error("expected an integer");
      if (errno == ERANGE) throw Error("out of range [-2^63, 2^64)");
      *value = static_cast<unsigned long>(v);  // two's complement, as a former `int` seed
    } else {
      const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
      if (text.empty() || end != text.c_str() + text.size() || !std::isdigit(static_cast<unsigned char>(text[0]))) {
        throw Error("expected an integer");
      }
      if (errno == ERANGE) throw Error("out of range [-2^63, 2^64)");
      *value = static_cast<unsigned long>(v);
    }
  };
  RegisterSpec(std::move(spec));
}

void OptionsItf::Register(const std::string& name, float* value, const std::string& help) {
  OptionSpec spec = single_valued(name, help, value, [](float v, int digits) { return format_double(v, digits); });
  spec.default_text = format_double(*value, 7);
  spec.set = [value](const std::string& text) { *value = static_cast<float>(to_double(text)); };
  RegisterSpec(std::move(spec));
}

void OptionsItf::Register(const std::string& name, double* value, const std::string& help) {
  OptionSpec spec = single_valued(name, help, value, [](double v, int digits) { return format_double(v, digits); });
  spec.default_text = format_double(*value, 10);
  spec.set = [value](const std::string& text) { *value = to_double(text); };
  RegisterSpec(std::move(spec));
}

void OptionsItf::Register(const std::string& name, std::string* value, const std::string& help) {
  OptionSpec spec = single_valued(name, help, value, [](const std::string& v, int) { return v; });
  spec.default_text = *value;
  spec.set = [value](const std::string& text) { *value = text; };
  RegisterSpec(std::move(spec));
}

void OptionsItf::Register(const std::string& name, std::vector<std::string>* values, const std::string& help) {
  OptionSpec spec;
  spec.name = name;
  spec.help = help + " (may be repeated)";
  spec.repeated = true;
  spec.get = [values](int) { return *values; };
  spec.set = [values](const std::string& text) { values->push_back(text); };
  spec.clear = [values]() { values->clear(); };
  RegisterSpec(std::move(spec));
}

void throw_unknown_choice(const std::string& expected) { throw Error("expected one of: " + expected); }

void throw_unknown_name(const std::string& what, const std::string& text, const std::string& expected) {
  throw Error("unknown " + what + " '" + text + "' (expected " + expected + ")");
}

}  // namespace tsrir
