#include "sim/mic_array.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "io/rxfile.h"
#include "util/commented_lines.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// "key=value" fields after the kind; every key must be one of `known` (missing ones: no entry).
std::map<std::string, double> kind_parameters(const std::vector<std::string>& fields,
                                              const std::vector<std::string>& known, const std::string& context) {
  std::map<std::string, double> out;
  std::string names;
  for (const std::string& k : known) names += (names.empty() ? "" : ", ") + k + "=";
  for (size_t i = 1; i < fields.size(); ++i) {
    const size_t eq = fields[i].find('=');
    const std::string key = eq == std::string::npos ? fields[i] : fields[i].substr(0, eq);
    if (eq == std::string::npos || std::find(known.begin(), known.end(), key) == known.end() || out.count(key)) {
      throw Error(context + ": expected each of " + names + " at most once, got '" + fields[i] + "'");
    }
    out[key] = parse_double(fields[i].substr(eq + 1), context + ": " + key);
  }
  return out;
}

double required(const std::map<std::string, double>& params, const std::string& key, const std::string& context) {
  auto it = params.find(key);
  if (it == params.end()) throw Error(context + ": missing " + key + "=");
  return it->second;
}

size_t mic_count(const std::map<std::string, double>& params, const std::string& context) {
  const double n = required(params, "n", context);
  if (!(n >= 1 && n <= 64 && n == std::floor(n))) throw Error(context + ": n must be a whole number in [1, 64]");
  return static_cast<size_t>(n);
}

std::vector<Vec3> linear_array(const std::vector<std::string>& fields, const std::string& context) {
  const auto params = kind_parameters(fields, {"n", "spacing_m", "azimuth_deg", "elevation_deg"}, context);
  const size_t n = mic_count(params, context);
  const double spacing = required(params, "spacing_m", context);
  if (!(spacing > 0.0 && spacing < 10.0)) throw Error(context + ": spacing_m must be in (0, 10) m");
  const Vec3 axis = axis_from_degrees(params.count("azimuth_deg") ? params.at("azimuth_deg") : 0.0,
                                      params.count("elevation_deg") ? params.at("elevation_deg") : 0.0);
  std::vector<Vec3> out;
  for (size_t k = 0; k < n; ++k) {
    const double along = (static_cast<double>(k) - 0.5 * (n - 1.0)) * spacing;
    out.push_back({along * axis[0], along * axis[1], along * axis[2]});
  }
  return out;
}

std::vector<Vec3> circular_array(const std::vector<std::string>& fields, const std::string& context) {
  const auto params = kind_parameters(fields, {"n", "radius_m", "start_deg"}, context);
  const size_t n = mic_count(params, context);
  const double radius = required(params, "radius_m", context);
  if (!(radius > 0.0 && radius < 10.0)) throw Error(context + ": radius_m must be in (0, 10) m");
  const double start = params.count("start_deg") ? params.at("start_deg") : 0.0;
  std::vector<Vec3> out;
  for (size_t k = 0; k < n; ++k) {
    const double azimuth = (start + 360.0 * k / n) * kPi / 180.0;
    out.push_back({radius * std::cos(azimuth), radius * std::sin(azimuth), 0.0});
  }
  return out;
}

}  // namespace

std::vector<Vec3> parse_array_geometry(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  CommentedLines lines(in);
  std::string line, kind;
  std::vector<Vec3> offsets;
  while (lines.next(&line)) {
    const std::vector<std::string> fields = split_whitespace(line);
    const std::string context = source + ":" + std::to_string(lines.lines_read());
    if (kind.empty()) {
      kind = fields[0];
      if (kind == "linear") {
        offsets = linear_array(fields, context);
      } else if (kind == "circular") {
        offsets = circular_array(fields, context);
      } else if (kind != "arbitrary" || fields.size() != 1) {
        throw Error(context + ": the first line must be 'linear ...', 'circular ...' or 'arbitrary', got '" +
                    trim(line) + "'");
      }
    } else if (kind == "arbitrary") {
      if (fields.size() != 3) throw Error(context + ": expected an offset 'dx dy dz' in metres");
      Vec3 offset{};
      for (int i = 0; i < 3; ++i) offset[i] = parse_double(fields[i], context + ": offset");
      offsets.push_back(offset);
    } else {
      throw Error(context + ": a " + kind + " array is one line; unexpected '" + trim(line) + "'");
    }
  }
  if (offsets.empty()) throw Error(source + ": the array geometry has no microphones");
  if (offsets.size() > 64) throw Error(source + ": more than 64 microphones");
  return offsets;
}

std::vector<Vec3> read_array_geometry(const std::string& path) {
  const std::vector<char> bytes = read_rxfile(path);
  return parse_array_geometry(std::string(bytes.begin(), bytes.end()), path);
}

std::string array_geometry_help() {
  return
      "Array geometry file (array=FILE): offsets from the line's mic= (the array centre), '#' comments.\n"
      "  linear n=N spacing_m=D [azimuth_deg=A elevation_deg=E]   N mics D m apart along axis (A,E), centred\n"
      "  circular n=N radius_m=R [start_deg=S]                    N mics on a horizontal circle, mic k at S+360k/N deg\n"
      "  arbitrary                                                then one 'dx dy dz' offset (m) per line\n";
}

}  // namespace tsrir::sim
