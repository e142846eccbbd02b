// Small, strict text parsing helpers: every failure is an Error naming the context.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace tsrir {

std::string trim(std::string_view s);
// Splits on runs of spaces/tabs; no empty fields.
std::vector<std::string> split_whitespace(std::string_view s);
// Splits on one character, keeping empty fields.
std::vector<std::string> split(std::string_view s, char sep);
bool starts_with(std::string_view s, std::string_view prefix);
bool ends_with(std::string_view s, std::string_view suffix);

// Whole-string numeric parsing; `context` goes into the error message (e.g. "rooms.txt:3: src").
double parse_double(std::string_view text, const std::string& context);
long long parse_int(std::string_view text, const std::string& context);
bool parse_bool(std::string_view text, const std::string& context);  // true/false, case-insensitive
// "a,b,c" -> doubles.
std::vector<double> parse_double_list(std::string_view text, char sep, const std::string& context);

// Formats a double with `digits` significant digits, no trailing noise ("0.5", "1e-06").
std::string format_double(double v, int digits = 6);

}  // namespace tsrir
