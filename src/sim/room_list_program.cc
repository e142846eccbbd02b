#include "sim/room_list_program.h"

#include <cstdint>

#include "io/atomic_output.h"
#include "io/common_options.h"
#include "sim/room_list.h"
#include "util/error.h"
#include "util/log.h"
#include "util/strings.h"

namespace tsrir::sim {
namespace {

const Choices<MetadataFormat>& metadata_format_choices() {
  static const Choices<MetadataFormat> choices = {
      {"r3vival", MetadataFormat::kR3vival}, {"but", MetadataFormat::kBut}, {"table", MetadataFormat::kTable}};
  return choices;
}

// A seed as a person wrote it: those given as negative numbers (two's complement) print negative.
std::string seed_text(Seed seed) {
  const auto as_signed = static_cast<int64_t>(seed);
  return as_signed < 0 ? std::to_string(as_signed) : std::to_string(seed);
}

}  // namespace

void RoomListCommand::Register(OptionsItf* opts) {
  opts->RegisterEnum("format", &format, metadata_format_choices(), "input format");
  opts->Register("absorption-range", &absorption_range, "min,max of the uniform absorption draw, within (0,1]");
  opts->RegisterEnum("absorption-draw", &draw.draw, absorption_draw_choices(),
                     "what gets its own draw: rir (one value for the room), surface (one per surface, flat over "
                     "bands), surface-band (one per surface and octave band)");
  opts->Register("scattering", &draw.scattering, "scattering coefficient written for every RIR");
  CommonOptions(opts).seed(&draw.seed, "the absorption draws");
  opts->Register("room", &room, "r3vival: room size Lx,Ly,Lz in metres");
  opts->Register("source-height", &source_height_m, "r3vival: source height in metres (not published)");
  opts->Register("mic-height", &mic_height_m, "r3vival: microphone height in metres (not published)");
  opts->Register("conditions", &conditions, "r3vival: comma-separated condition names, one RIR per condition and source");
  opts->Register("id-format", &id_format,
                 "r3vival: rir id with {condition}, {source}, {s_source} (default {s_source}, or "
                 "r3vival_{condition}_{s_source} with --conditions)");
}

size_t run_rir_room_list(const RoomListCommand& c, const std::string& metadata, const std::string& room_list_out) {
  std::vector<MetadataSetup> setups;
  switch (c.format) {
    case MetadataFormat::kR3vival: {
      R3vivalOptions options;
      const std::vector<double> size = parse_double_list(c.room, ',', "--room");
      if (size.size() != 3) throw Error("--room needs Lx,Ly,Lz");
      options.room_m = {size[0], size[1], size[2]};
      options.source_height_m = c.source_height_m;
      options.mic_height_m = c.mic_height_m;
      if (!c.conditions.empty()) options.conditions = split(c.conditions, ',');
      options.id_format = !c.id_format.empty() ? c.id_format
                          : c.conditions.empty() ? "{s_source}"
                                                 : "r3vival_{condition}_{s_source}";
      setups = read_r3vival_positions(metadata, options);
      break;
    }
    case MetadataFormat::kBut: {
      std::vector<std::string> skipped;
      setups = read_but_reverbdb(metadata, &skipped);
      for (const std::string& s : skipped) log_warning("skipped " + s);
      break;
    }
    case MetadataFormat::kTable:
      setups = read_setup_table(metadata);
      break;
  }
  RoomDrawOptions draw = c.draw;
  const std::vector<double> range = parse_double_list(c.absorption_range, ',', "--absorption-range");
  if (range.size() != 2) throw Error("--absorption-range needs min,max");
  draw.absorption_min = range[0];
  draw.absorption_max = range[1];
  const std::vector<RoomSpec> rooms = rooms_from_setups(setups, draw);

  std::string header = std::string("# made by rir-room-list --format=") + choice_name(metadata_format_choices(), c.format) +
                       " --absorption-range=" + c.absorption_range + " --absorption-draw=" + choice_name(absorption_draw_choices(), draw.draw) +
                       " --seed=" + seed_text(draw.seed) + " from " + metadata;
  // A newline in the input's name or an option would end the comment and leave a bad line.
  for (char& ch : header) {
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = '?';
  }
  AtomicTextFile out(room_list_out);
  out.stream() << header << "\n";
  for (const RoomSpec& r : rooms) out.stream() << format_room_list_line(r) << "\n";
  out.commit();
  return rooms.size();
}

}  // namespace tsrir::sim
