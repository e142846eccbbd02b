#include "sim/room_list.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "io/rxfile.h"
#include "sim/mic_array.h"
#include "util/commented_lines.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir::sim {
namespace {

std::optional<int> surface_from_name(const std::string& name) {
  for (int s = 0; s < kNumSurfaces; ++s) {
    if (name == surface_name(s)) return s;
  }
  return std::nullopt;
}

Vec3 parse_vec3(const std::string& value, const std::string& key, const std::string& context) {
  const std::vector<double> v = parse_double_list(value, ',', context + ": " + key);
  if (v.size() != 3) {
    throw Error(context + ": " + key + " needs 3 comma-separated values (metres), got '" + value + "'");
  }
  return {v[0], v[1], v[2]};
}

// One value (all bands) or 8 band values.
BandValues parse_band_values(const std::string& value, const std::string& key, const std::string& context) {
  const std::vector<double> v = parse_double_list(value, ',', context + ": " + key);
  BandValues out{};
  if (v.size() == 1) {
    out.fill(v[0]);
  } else if (v.size() == static_cast<size_t>(kNumOctaveBands)) {
    for (int b = 0; b < kNumOctaveBands; ++b) out[b] = v[b];
  } else {
    throw Error(context + ": " + key + " needs 1 or 8 comma-separated values (62.5 Hz .. 8 kHz), got " +
                std::to_string(v.size()));
  }
  for (int b = 0; b < kNumOctaveBands; ++b) {
    if (!std::isfinite(out[b])) throw Error(context + ": " + key + " has a non-finite value");
  }
  return out;
}

void check_absorption_range(const BandValues& a, const std::string& key, const std::string& context) {
  for (double x : a) {
    if (!(x > 0.0 && x <= 1.0)) {
      throw Error(context + ": " + key + "=" + format_double(x) + " is outside (0,1]");
    }
  }
}

bool all_equal(const BandValues& v) {
  for (double x : v) {
    if (x != v[0]) return false;
  }
  return true;
}

std::string format_band_values(const BandValues& v) {
  if (all_equal(v)) return format_double(v[0], 9);
  std::string out;
  for (int b = 0; b < kNumOctaveBands; ++b) out += (b ? "," : "") + format_double(v[b], 9);
  return out;
}

std::string format_vec3(const Vec3& v) {
  return format_double(v[0], 9) + "," + format_double(v[1], 9) + "," + format_double(v[2], 9);
}

std::string format_axis(const Vec3& axis) {
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  const double elevation = std::asin(std::clamp(axis[2], -1.0, 1.0)) * kRadToDeg;
  return format_double(std::atan2(axis[1], axis[0]) * kRadToDeg, 9) + "," + format_double(elevation, 9);
}

// The pattern keys, written only where given (so a mono omni line keeps its old text).
std::string format_transducer_keys(const RoomSpec& room) {
  std::string out;
  const Vec3 default_axis{1.0, 0.0, 0.0};
  if (room.mic_pattern) out += " mic_pattern=" + choice_name(polar_pattern_choices(), *room.mic_pattern);
  if (room.mic_axis != default_axis) out += " mic_dir=" + format_axis(room.mic_axis);
  if (room.source_pattern) out += " src_pattern=" + choice_name(polar_pattern_choices(), *room.source_pattern);
  if (room.source_band_patterns) {
    out += " src_pattern_bands=";
    for (size_t b = 0; b < room.source_band_patterns->size(); ++b)
      out += (b ? "," : "") + choice_name(polar_pattern_choices(), (*room.source_band_patterns)[b]);
  }
  if (room.source_axis != default_axis) out += " src_dir=" + format_axis(room.source_axis);
  return out;
}

// The keys of microphones, arrays and polar patterns, kept apart from the room's own keys.
struct TransducerKeys {
  std::optional<std::vector<Vec3>> mics;     // mic=x,y,z[;x,y,z...]
  std::optional<std::string> array_file;     // array=FILE (offsets from a single mic=)
  std::optional<PolarPattern> mic_pattern, source_pattern;
  std::optional<std::array<PolarPattern, kNumOctaveBands>> source_band_patterns;  // src_pattern_bands=
  std::optional<Vec3> mic_axis, source_axis;
};

// src_pattern_bands=P62.5,P125,...,P8000: one pattern name per octave band.
std::array<PolarPattern, kNumOctaveBands> parse_band_patterns(const std::string& value, const std::string& context) {
  const std::vector<std::string> names = split(value, ',');
  if (names.size() != kNumOctaveBands)
    throw Error(context + ": src_pattern_bands needs " + std::to_string(kNumOctaveBands) +
                " comma-separated patterns (62.5 Hz .. 8 kHz), got " + std::to_string(names.size()));
  std::array<PolarPattern, kNumOctaveBands> patterns{};
  for (size_t b = 0; b < names.size(); ++b)
    patterns[b] = parse_choice(polar_pattern_choices(), trim(names[b]), context + ": src_pattern_bands");
  return patterns;
}

Vec3 parse_axis(const std::string& value, const std::string& key, const std::string& context) {
  const std::vector<double> v = parse_double_list(value, ',', context + ": " + key);
  if (v.size() != 2 || !std::isfinite(v[0]) || !(v[1] >= -90.0 && v[1] <= 90.0)) {
    throw Error(context + ": " + key + " needs azimuth,elevation in degrees (elevation in [-90, 90]), got '" +
                value + "'");
  }
  return axis_from_degrees(v[0], v[1]);
}

// True when `key` is one of these keys (then parsed into *keys).
bool parse_transducer_key(const std::string& key, const std::string& value, const std::string& context,
                          TransducerKeys* keys) {
  if (key == "mic") {
    keys->mics.emplace();
    for (const std::string& one : split(value, ';')) keys->mics->push_back(parse_vec3(one, key, context));
  } else if (key == "array") {
    if (value.empty()) throw Error(context + ": empty array= file name");
    keys->array_file = value;
  } else if (key == "mic_pattern" || key == "src_pattern") {
    const PolarPattern p = parse_choice(polar_pattern_choices(), value, context + ": " + key);
    (key == "mic_pattern" ? keys->mic_pattern : keys->source_pattern) = p;
  } else if (key == "src_pattern_bands") {
    keys->source_band_patterns = parse_band_patterns(value, context);
  } else if (key == "mic_dir" || key == "src_dir") {
    (key == "mic_dir" ? keys->mic_axis : keys->source_axis) = parse_axis(value, key, context);
  } else {
    return false;
  }
  return true;
}

void apply_transducer_keys(const TransducerKeys& keys, const std::string& context, RoomSpec* room) {
  if (!keys.mics) throw Error(context + ": missing mic=x,y,z");
  room->mic_m = keys.mics->front();
  if (keys.mics->size() > 1) room->array_m = *keys.mics;
  if (keys.array_file) {
    if (keys.mics->size() > 1) throw Error(context + ": with array=, mic= is the array centre (one position)");
    const Vec3 centre = room->mic_m;
    for (const Vec3& offset : read_array_geometry(*keys.array_file)) {
      room->array_m.push_back({centre[0] + offset[0], centre[1] + offset[1], centre[2] + offset[2]});
    }
    room->mic_m = room->array_m.front();
    if (room->array_m.size() == 1) room->array_m.clear();
  }
  if (room->array_m.size() > 64) throw Error(context + ": more than 64 microphones");
  room->mic_pattern = keys.mic_pattern;
  if (keys.source_pattern && keys.source_band_patterns)
    throw Error(context + ": give src_pattern (every band) or src_pattern_bands (one per band), not both");
  room->source_pattern = keys.source_pattern;
  room->source_band_patterns = keys.source_band_patterns;
  if (keys.mic_axis) room->mic_axis = *keys.mic_axis;
  if (keys.source_axis) room->source_axis = *keys.source_axis;
}

}  // namespace

RoomSpec parse_room_list_line(const std::string& line, const std::string& context) {
  const std::vector<std::string> fields = split_whitespace(line);
  if (fields.empty()) throw Error(context + ": empty room-list line");
  RoomSpec room;
  room.where = context;
  room.rir_id = fields[0];
  if (room.rir_id.find('=') != std::string::npos) {
    throw Error(context + ": a line must start with the rir id, got '" + room.rir_id + "'");
  }
  if (room.rir_id.find('/') != std::string::npos || room.rir_id == "." || room.rir_id == "..") {
    throw Error(context + ": rir id '" + room.rir_id + "' cannot be used as a file name");
  }

  std::set<std::string> seen;
  std::optional<Vec3> size, src;
  TransducerKeys transducers;
  std::optional<BandValues> absorption_all, absorption_walls, scattering, t60;
  std::optional<BandValues> absorption_surface[kNumSurfaces];
  std::optional<double> temperature, humidity;
  for (size_t i = 1; i < fields.size(); ++i) {
    const std::string& field = fields[i];
    const size_t eq = field.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw Error(context + ": expected key=value, got '" + field + "'");
    }
    const std::string key = field.substr(0, eq);
    const std::string value = field.substr(eq + 1);
    if (!seen.insert(key).second) throw Error(context + ": key '" + key + "' given twice");
    if (parse_transducer_key(key, value, context, &transducers)) {
      continue;
    } else if (key == "room") {
      size = parse_vec3(value, key, context);
    } else if (key == "src") {
      src = parse_vec3(value, key, context);
    } else if (key == "absorption") {
      absorption_all = parse_band_values(value, key, context);
      check_absorption_range(*absorption_all, key, context);
    } else if (key == "absorption.walls") {
      absorption_walls = parse_band_values(value, key, context);
      check_absorption_range(*absorption_walls, key, context);
    } else if (starts_with(key, "absorption.")) {
      const std::optional<int> s = surface_from_name(key.substr(11));
      if (!s) {
        throw Error(context + ": unknown surface in '" + key +
                    "' (use x0, x1, y0, y1, floor, ceiling or walls)");
      }
      absorption_surface[*s] = parse_band_values(value, key, context);
      check_absorption_range(*absorption_surface[*s], key, context);
    } else if (key == "scattering") {
      scattering = parse_band_values(value, key, context);
      for (double x : *scattering) {
        if (!(x >= 0.0 && x <= 1.0)) {
          throw Error(context + ": scattering=" + format_double(x) + " is outside [0,1]");
        }
      }
    } else if (key == "t60") {
      t60 = parse_band_values(value, key, context);
    } else if (key == "room-id") {
      if (value.empty()) throw Error(context + ": empty room-id");
      room.room_id = value;
    } else if (key == "temperature") {
      temperature = parse_double(value, context + ": temperature");
      if (!(*temperature > -50.0 && *temperature < 60.0)) {
        throw Error(context + ": temperature=" + value + " C is outside (-50, 60)");
      }
    } else if (key == "humidity") {
      humidity = parse_double(value, context + ": humidity");
      if (!(*humidity >= 0.0 && *humidity <= 100.0)) {
        throw Error(context + ": humidity=" + value + " % is outside [0, 100]");
      }
    } else {
      throw Error(context + ": unknown key '" + key + "' (known: " +
                  "room src mic array mic_pattern mic_dir src_pattern src_pattern_bands src_dir absorption absorption.<surface> "
                  "scattering t60 room-id temperature humidity)");
    }
  }
  if (!size) throw Error(context + ": missing room=Lx,Ly,Lz");
  if (!src) throw Error(context + ": missing src=x,y,z");
  room.size_m = *size;
  room.source_m = *src;
  apply_transducer_keys(transducers, context, &room);
  if (temperature) {
    room.temperature_c = *temperature;
    room.speed_of_sound_m_s = speed_of_sound_from_temperature_m_s(*temperature);
  }
  if (humidity) room.relative_humidity_percent = *humidity;
  room.scattering = scattering ? *scattering : BandValues{};
  if (!scattering) room.scattering.fill(kDefaultScattering);

  bool any_absorption = absorption_all || absorption_walls;
  for (int s = 0; s < kNumSurfaces; ++s) any_absorption = any_absorption || absorption_surface[s];
  // Geometry first, so that t60 inversion (which needs V and S) sees valid dimensions.
  room.absorption.fill(BandValues{});
  for (auto& a : room.absorption) a.fill(kDefaultAbsorption);
  validate_room(room);
  if (t60) {
    if (any_absorption) throw Error(context + ": give either t60 or absorption keys, not both");
    for (int b = 0; b < kNumOctaveBands; ++b) {
      const double a = eyring_absorption_for_t60((*t60)[b], room.volume_m3(), room.surface_area_m2(),
                                                 room.speed_of_sound_m_s,
                                                 context + " (" + octave_band_label(kOctaveCentersHz[b]) + " Hz)");
      for (int s = 0; s < kNumSurfaces; ++s) room.absorption[s][b] = a;
    }
  } else {
    for (int s = 0; s < kNumSurfaces; ++s) {
      const bool is_wall = s < kFloor;
      if (absorption_surface[s]) {
        room.absorption[s] = *absorption_surface[s];
      } else if (is_wall && absorption_walls) {
        room.absorption[s] = *absorption_walls;
      } else if (absorption_all) {
        room.absorption[s] = *absorption_all;
      }
    }
  }
  validate_room(room);
  return room;
}

std::vector<RoomSpec> parse_room_list(const std::string& text, const std::string& source) {
  std::vector<RoomSpec> rooms;
  std::set<std::string> ids;
  std::istringstream in(text);
  CommentedLines lines(in);
  std::string line;
  while (lines.next(&line)) {
    const std::string context = source + ":" + std::to_string(lines.lines_read());
    RoomSpec room = parse_room_list_line(line, context);
    if (!ids.insert(room.rir_id).second) {
      throw Error(context + ": duplicate rir id '" + room.rir_id + "'");
    }
    rooms.push_back(std::move(room));
  }
  if (rooms.empty()) throw Error(source + ": the room list has no entries");
  return rooms;
}

std::vector<RoomSpec> read_room_list(const std::string& path) {
  const std::vector<char> bytes = read_rxfile(path);
  return parse_room_list(std::string(bytes.begin(), bytes.end()), path);
}

std::string format_room_list_line(const RoomSpec& room) {
  std::string out = room.rir_id;
  out += " room=" + format_vec3(room.size_m);
  out += " src=" + format_vec3(room.source_m);
  out += " mic=";
  for (size_t m = 0; m < room.num_mics(); ++m) out += (m ? ";" : "") + format_vec3(room.mic_position_m(m));
  out += format_transducer_keys(room);
  bool uniform = true;
  for (int s = 1; s < kNumSurfaces; ++s) uniform = uniform && room.absorption[s] == room.absorption[0];
  if (uniform) {
    out += " absorption=" + format_band_values(room.absorption[0]);
  } else {
    for (int s = 0; s < kNumSurfaces; ++s) {
      out += std::string(" absorption.") + surface_name(s) + "=" + format_band_values(room.absorption[s]);
    }
  }
  out += " scattering=" + format_band_values(room.scattering);
  if (!room.room_id.empty()) out += " room-id=" + room.room_id;
  if (room.speed_of_sound_m_s != kDefaultSpeedOfSound_m_s || room.temperature_c != 20.0) {
    out += " temperature=" + format_double(room.temperature_c, 9);
  }
  if (room.relative_humidity_percent != 50.0) {
    out += " humidity=" + format_double(room.relative_humidity_percent, 9);
  }
  return out;
}

std::string room_list_keys_help() {
  return
      "Room list: one RIR per line, '<rir-id> key=value ...'; blank lines and '#' comments ignored.\n"
      "  room=Lx,Ly,Lz        shoebox size in metres (required); the room spans [0,Lx]x[0,Ly]x[0,Lz], z up\n"
      "  src=x,y,z mic=x,y,z  source and microphone positions in metres, strictly inside (required)\n"
      "  mic=x,y,z;x,y,z;...  a microphone array: one multichannel RIR, channels in this order\n"
      "  array=FILE           an array from a geometry file (below), centred on mic=\n"
      "  mic_pattern=P        polar pattern of the microphone(s): omni (default), subcardioid, cardioid,\n"
      "                       hypercardioid, figure8 (g = a + (1-a) cos theta, a = 1, .75, .5, .25, 0)\n"
      "  mic_dir=AZ,EL        their axis: azimuth (deg from +x towards +y), elevation (deg); default 0,0\n"
      "  src_pattern=P src_dir=AZ,EL   the same for the source (default omni)\n"
      "  src_pattern_bands=P,...  a loudspeaker's pattern per octave band, 8 names (62.5 Hz .. 8 kHz)\n"
      "  absorption=A         energy absorption of all six surfaces, in (0,1]; one value or 8 band values\n"
      "                       a63,a125,a250,a500,a1k,a2k,a4k,a8k (default 0.2)\n"
      "  absorption.walls=A   the four walls (x0,x1,y0,y1); overrides absorption=\n"
      "  absorption.S=A       one surface S in x0 (x=0), x1 (x=Lx), y0, y1, floor (z=0), ceiling (z=Lz);\n"
      "                       overrides absorption.walls= and absorption=\n"
      "  scattering=S         fraction of reflected energy scattered diffusely, [0,1], 1 or 8 values (default 0.1)\n"
      "  t60=T                target reverberation time (s), 1 or 8 values: all surfaces get the absorption\n"
      "                       that Eyring's formula needs (exclusive with absorption keys; a T60 needing a\n"
      "                       mean absorption below 0.01 is rejected as unreachable)\n"
      "  room-id=R            Kaldi room id written to rir_list (default: the rir id)\n"
      "  temperature=C        air temperature; sets c = 331.3 sqrt(1 + C/273.15) (default c = 343 m/s)\n"
      "  humidity=H           relative humidity in % (used by air-absorption components; default 50)\n" +
      array_geometry_help();
}

}  // namespace tsrir::sim
