#include "sim/room_list.h"

#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "io/rxfile.h"
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
  std::optional<Vec3> size, src, mic;
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
    if (key == "room") {
      size = parse_vec3(value, key, context);
    } else if (key == "src") {
      src = parse_vec3(value, key, context);
    } else if (key == "mic") {
      mic = parse_vec3(value, key, context);
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
                  "room src mic absorption absorption.<surface> scattering t60 room-id temperature humidity)");
    }
  }
  if (!size) throw Error(context + ": missing room=Lx,Ly,Lz");
  if (!src) throw Error(context + ": missing src=x,y,z");
  if (!mic) throw Error(context + ": missing mic=x,y,z");
  room.size_m = *size;
  room.source_m = *src;
  room.mic_m = *mic;
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
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (trim(line).empty()) continue;
    const std::string context = source + ":" + std::to_string(line_number);
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
  out += " mic=" + format_vec3(room.mic_m);
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
      "  humidity=H           relative humidity in % (used by air-absorption components; default 50)\n";
}

}  // namespace tsrir::sim
