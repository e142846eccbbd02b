#include "sim/room_metadata.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "sim/room_list.h"
#include "util/commented_lines.h"
#include "util/error.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir::sim {
namespace fs = std::filesystem;
namespace {

std::string read_text(const std::string& path) {
  // An ifstream opens a directory and reads nothing: say what is wrong instead of "no rows".
  if (fs::is_directory(path)) throw Error(path + ": is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t pos = s.find(from); pos != std::string::npos; pos = s.find(from, pos + to.size())) {
    s.replace(pos, from.size(), to);
  }
  return s;
}

// "$Key<TAB>value" lines -> map (other lines ignored).
std::map<std::string, std::string> read_but_meta(const std::string& path) {
  std::map<std::string, std::string> out;
  std::istringstream in(read_text(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '$') continue;
    const std::vector<std::string> f = split_whitespace(line);
    if (f.size() >= 2) out[f[0].substr(1)] = f[1];
  }
  return out;
}

double meta_number(const std::map<std::string, std::string>& meta, const std::string& key, const std::string& path) {
  auto it = meta.find(key);
  if (it == meta.end()) throw Error(path + ": missing $" + key);
  return parse_double(it->second, path + ": $" + key);
}

std::vector<fs::path> sorted_subdirs(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory()) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The id as it can be shown in one line of a message (control bytes as \xNN).
std::string printable(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

// An id goes into a room list as one whitespace-separated word: whitespace would split it, '#'
// would start a comment, control bytes break the Kaldi tables rir-simulate writes from it.
void check_list_word(const std::string& id, const char* what, const std::string& where) {
  if (id.empty()) throw Error(where + ": empty " + what);
  for (unsigned char c : id) {
    if (c <= 0x20 || c == 0x7f || c == '#') {
      throw Error(where + ": " + what + " '" + printable(id) +
                  "' cannot be written to a room list (whitespace, control character or '#')");
    }
  }
}

bool inside(const Vec3& p, const Vec3& size) {
  for (int i = 0; i < 3; ++i) {
    if (!(p[i] > 0.0 && p[i] < size[i])) return false;
  }
  return true;
}

}  // namespace

std::vector<MetadataSetup> read_r3vival_positions(const std::string& csv_path, const R3vivalOptions& options) {
  std::istringstream in(read_text(csv_path));
  std::string line;
  int line_number = 0;
  std::map<std::string, int> column;
  struct Source { std::string id; double x, y; int line; };
  std::vector<Source> sources;
  std::optional<std::pair<double, double>> receiver;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty()) continue;
    const std::vector<std::string> f = split(line, ',');
    const std::string where = csv_path + ":" + std::to_string(line_number);
    if (column.empty()) {
      for (size_t i = 0; i < f.size(); ++i) column[trim(f[i])] = static_cast<int>(i);
      for (const char* need : {"source_id", "x_m_approx", "y_m_approx", "source_type"}) {
        if (!column.count(need)) throw Error(where + ": header lacks column '" + need + "'");
      }
      continue;
    }
    if (f.size() < column.size()) throw Error(where + ": expected " + std::to_string(column.size()) + " fields");
    const double x = parse_double(trim(f[column["x_m_approx"]]), where + ": x_m_approx");
    const double y = parse_double(trim(f[column["y_m_approx"]]), where + ": y_m_approx");
    if (trim(f[column["source_type"]]) == "receiver") {
      if (receiver) throw Error(where + ": a second receiver row");
      receiver = {x, y};
    } else {
      sources.push_back({trim(f[column["source_id"]]), x, y, line_number});
    }
  }
  if (!receiver) throw Error(csv_path + ": no row with source_type 'receiver'");
  if (sources.empty()) throw Error(csv_path + ": no source rows");
  std::vector<std::string> conditions = options.conditions;
  if (conditions.empty()) conditions.push_back("");
  std::vector<MetadataSetup> out;
  for (const std::string& condition : conditions) {
    for (const Source& s : sources) {
      MetadataSetup setup;
      const std::string s_source = starts_with(s.id, "S") ? s.id : "S" + s.id;
      std::string id = replace_all(options.id_format, "{condition}", condition);
      id = replace_all(replace_all(id, "{s_source}", s_source), "{source}", s.id);
      setup.rir_id = id;
      setup.room_id = condition.empty() ? "r3vival" : "r3vival_" + condition;
      setup.size_m = options.room_m;
      setup.source_m = {s.x, s.y, options.source_height_m};
      setup.mic_m = {receiver->first, receiver->second, options.mic_height_m};
      setup.where = csv_path + ":" + std::to_string(s.line);
      out.push_back(setup);
    }
  }
  return out;
}

std::vector<MetadataSetup> read_but_reverbdb(const std::string& root, std::vector<std::string>* skipped) {
  if (!fs::is_directory(root)) throw Error(root + ": not a directory (expected the BUT ReverbDB root)");
  std::vector<MetadataSetup> out;
  size_t skipped_count = 0;
  std::string first_skipped;
  for (const fs::path& room_dir : sorted_subdirs(root)) {
    const fs::path env = room_dir / "env_meta.txt";
    if (!fs::exists(env)) continue;
    const auto env_meta = read_but_meta(env.string());
    const Vec3 size{meta_number(env_meta, "EnvDepth", env.string()), meta_number(env_meta, "EnvWidth", env.string()),
                    meta_number(env_meta, "EnvHeight", env.string())};
    const std::string room = room_dir.filename().string();
    for (const fs::path& config_dir : sorted_subdirs(room_dir)) {
      for (const fs::path& spk_dir : sorted_subdirs(config_dir)) {
        const fs::path spk_file = spk_dir / "spk_meta.txt";
        if (!fs::exists(spk_file)) continue;
        const auto spk = read_but_meta(spk_file.string());
        const Vec3 src{meta_number(spk, "EnvSpk1Depth", spk_file.string()),
                       meta_number(spk, "EnvSpk1Width", spk_file.string()),
                       meta_number(spk, "EnvSpk1Height", spk_file.string())};
        for (const fs::path& mic_dir : sorted_subdirs(spk_dir)) {
          const fs::path mic_file = mic_dir / "mic_meta.txt";
          if (!fs::exists(mic_file)) continue;
          const auto mic_meta = read_but_meta(mic_file.string());
          auto id_it = mic_meta.find("EnvMicID");
          if (id_it == mic_meta.end()) throw Error(mic_file.string() + ": missing $EnvMicID");
          const std::string n = id_it->second;
          const Vec3 mic{meta_number(mic_meta, "EnvMic" + n + "Depth", mic_file.string()),
                         meta_number(mic_meta, "EnvMic" + n + "Width", mic_file.string()),
                         meta_number(mic_meta, "EnvMic" + n + "Height", mic_file.string())};
          if (!inside(src, size) || !inside(mic, size)) {
            const std::string reason = mic_file.string() + ": " + (!inside(src, size) ? "source" : "microphone") +
                                       " outside the room given in " + env.string();
            if (skipped_count++ == 0) first_skipped = reason;
            if (skipped) skipped->push_back(reason);
            continue;
          }
          MetadataSetup setup;
          setup.rir_id = room + "_" + config_dir.filename().string() + "_" + spk_dir.filename().string() + "_" +
                         mic_dir.filename().string();
          setup.room_id = room;
          setup.size_m = size;
          setup.source_m = src;
          setup.mic_m = mic;
          setup.where = mic_file.string();
          out.push_back(setup);
        }
      }
    }
  }
  if (out.empty() && skipped_count > 0) {
    // The caller prints the skipped list only on success: the error itself must say why.
    throw Error(root + ": all " + std::to_string(skipped_count) + " set-ups lie outside their rooms; first: " +
                first_skipped);
  }
  if (out.empty()) throw Error(root + ": no RIR metadata found (expected <room>/env_meta.txt and "
                                      "<room>/<config>/<speaker>/<mic>/mic_meta.txt)");
  return out;
}

std::vector<MetadataSetup> read_setup_table(const std::string& path) {
  std::istringstream in(read_text(path));
  CommentedLines lines(in);
  std::string line;
  std::map<std::string, size_t> column;
  std::vector<MetadataSetup> out;
  const char* const kNeeded[] = {"rir-id", "Lx", "Ly", "Lz", "sx", "sy", "sz", "mx", "my", "mz"};
  while (lines.next(&line)) {
    const std::vector<std::string> f = split_whitespace(line);
    const std::string where = path + ":" + std::to_string(lines.lines_read());
    if (column.empty()) {
      for (size_t i = 0; i < f.size(); ++i) column[f[i]] = i;
      for (const char* need : kNeeded) {
        if (!column.count(need)) throw Error(where + ": header lacks column '" + need + "'");
      }
      continue;
    }
    if (f.size() != column.size()) {
      throw Error(where + ": expected " + std::to_string(column.size()) + " fields, got " + std::to_string(f.size()));
    }
    auto num = [&](const char* name) { return parse_double(f[column[name]], where + ": " + name); };
    MetadataSetup s;
    s.rir_id = f[column["rir-id"]];
    if (column.count("room-id")) s.room_id = f[column["room-id"]];
    s.size_m = {num("Lx"), num("Ly"), num("Lz")};
    s.source_m = {num("sx"), num("sy"), num("sz")};
    s.mic_m = {num("mx"), num("my"), num("mz")};
    s.where = where;
    out.push_back(s);
  }
  if (out.empty()) throw Error(path + ": no setups in the table");
  return out;
}

const Choices<AbsorptionDraw>& absorption_draw_choices() {
  static const Choices<AbsorptionDraw> choices = {{"rir", AbsorptionDraw::kPerRir},
                                                  {"surface", AbsorptionDraw::kPerSurface},
                                                  {"surface-band", AbsorptionDraw::kPerSurfaceBand}};
  return choices;
}

std::vector<RoomSpec> rooms_from_setups(const std::vector<MetadataSetup>& setups, const RoomDrawOptions& options) {
  if (!(options.absorption_min > 0.0 && options.absorption_min <= options.absorption_max &&
        options.absorption_max <= 1.0)) {
    throw Error("--absorption-range must satisfy 0 < min <= max <= 1, got " + format_double(options.absorption_min) +
                "," + format_double(options.absorption_max));
  }
  if (!(options.scattering >= 0.0 && options.scattering <= 1.0)) throw Error("--scattering must be in [0,1]");
  std::vector<RoomSpec> rooms;
  std::set<std::string> ids;
  for (const MetadataSetup& s : setups) {
    if (!ids.insert(s.rir_id).second) throw Error(s.where + ": duplicate rir id '" + s.rir_id + "'");
    RoomSpec room;
    room.rir_id = s.rir_id;
    room.room_id = s.room_id == s.rir_id ? "" : s.room_id;
    room.size_m = s.size_m;
    room.source_m = s.source_m;
    room.mic_m = s.mic_m;
    room.where = s.where;
    room.scattering.fill(options.scattering);
    Rng rng = Rng::for_item(options.seed, s.rir_id);
    auto draw = [&] { return rng.uniform(options.absorption_min, options.absorption_max); };
    const double per_rir = draw();
    for (int surface = 0; surface < kNumSurfaces; ++surface) {
      const double per_surface = options.draw == AbsorptionDraw::kPerRir ? per_rir : draw();
      for (int b = 0; b < kNumOctaveBands; ++b) {
        room.absorption[surface][b] = options.draw == AbsorptionDraw::kPerSurfaceBand ? draw() : per_surface;
      }
    }
    validate_room(room);
    check_list_word(room.rir_id, "rir id", s.where);
    if (!room.room_id.empty()) check_list_word(room.room_id, "room id", s.where);
    // What rir-simulate will read is the written line: the room must survive it (a position a
    // hair inside a wall lands on it at 9 significant digits; an id rir-simulate refuses).
    RoomSpec written;
    try {
      written = parse_room_list_line(format_room_list_line(room), s.where);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + " (read back from the room-list line as written; positions have 9 significant digits)");
    }
    if (written.rir_id != room.rir_id || written.effective_room_id() != room.effective_room_id()) {
      throw Error(s.where + ": rir id '" + printable(room.rir_id) + "' / room id '" + printable(room.room_id) +
                  "' would not read back from a room list");
    }
    rooms.push_back(room);
  }
  return rooms;
}

}  // namespace tsrir::sim
