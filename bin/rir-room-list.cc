// rir-room-list: room lists for rir-simulate from measured-RIR metadata, with random absorption.
#include <string>

#include "io/atomic_output.h"
#include "sim/room_list.h"
#include "sim/room_metadata.h"
#include "util/cli.h"
#include "util/error.h"
#include "util/strings.h"

int main(int argc, char** argv) {
  using namespace tsrir;
  return run_program("rir-room-list", [&]() {
    CommandLine cli("rir-room-list",
                    "Turns room metadata of measured RIRs into a room list for rir-simulate (one line per RIR:\n"
                    "room size, source and microphone positions), drawing random surface absorption per RIR\n"
                    "as the TS-RIR paper does (uniform in --absorption-range; seeded by --seed and the rir id).\n\n"
                    "Usage: rir-room-list [options] <metadata> <room-list-out|->\n"
                    "Input formats (--format):\n"
                    "  r3vival  the R3VIVAL positions CSV (positions_approx_from_Plan_png.csv); room 9.7 x 5.5 x 2.7 m;\n"
                    "           heights are not published, so --source-height/--mic-height (default 1.35 m, the\n"
                    "           middle of the 1.2-1.5 m the dataset notes suggest) are used\n"
                    "  but      a BUT ReverbDB root directory (<room>/env_meta.txt, .../<speaker>/spk_meta.txt,\n"
                    "           .../<mic>/mic_meta.txt); x = depth, y = width, z = height; RIRs whose source or\n"
                    "           microphone lies outside the stated room are skipped with a warning\n"
                    "  table    a whitespace table whose header names rir-id Lx Ly Lz sx sy sz mx my mz [room-id]\n"
                    "Examples:\n"
                    "  rir-room-list --format=r3vival --conditions=000,025,050,075,100 \\\n"
                    "    --id-format=RLRVarAcLab_Absorptive_{condition}_{s_source}_R1_FRL10cm_ch7 \\\n"
                    "    ../shared/data/rirs/r3vival/positions_approx_from_Plan_png.csv rooms.txt\n"
                    "  rir-room-list --format=but --absorption-range=0.05,0.5 BUT_ReverbDB_rel_19_06_RIR-Only rooms.txt\n");
    std::string format = "table", absorption_range = "0.1,0.6", draw = "surface", room = "9.7,5.5,2.7";
    std::string conditions, id_format;
    double scattering = 0.1, source_height = 1.35, mic_height = 1.35;
    int seed = 0;
    cli.option("format", &format, "input format: r3vival | but | table");
    cli.option("absorption-range", &absorption_range, "min,max of the uniform absorption draw, within (0,1]");
    cli.option("absorption-draw", &draw,
               "what gets its own draw: rir (one value for the room), surface (one per surface, flat over "
               "bands), surface-band (one per surface and octave band)");
    cli.option("scattering", &scattering, "scattering coefficient written for every RIR");
    cli.option("seed", &seed, "random seed of the absorption draws");
    cli.option("room", &room, "r3vival: room size Lx,Ly,Lz in metres");
    cli.option("source-height", &source_height, "r3vival: source height in metres (not published)");
    cli.option("mic-height", &mic_height, "r3vival: microphone height in metres (not published)");
    cli.option("conditions", &conditions, "r3vival: comma-separated condition names, one RIR per condition and source");
    cli.option("id-format", &id_format,
               "r3vival: rir id with {condition}, {source}, {s_source} (default {s_source}, or "
               "r3vival_{condition}_{s_source} with --conditions)");
    const std::vector<std::string> args = cli.parse(argc, argv, 2, 2);

    std::vector<sim::MetadataSetup> setups;
    if (format == "r3vival") {
      sim::R3vivalOptions options;
      const std::vector<double> size = parse_double_list(room, ',', "--room");
      if (size.size() != 3) throw Error("--room needs Lx,Ly,Lz");
      options.room_m = {size[0], size[1], size[2]};
      options.source_height_m = source_height;
      options.mic_height_m = mic_height;
      if (!conditions.empty()) options.conditions = split(conditions, ',');
      options.id_format = !id_format.empty() ? id_format
                          : conditions.empty() ? "{s_source}"
                                               : "r3vival_{condition}_{s_source}";
      setups = sim::read_r3vival_positions(args[0], options);
    } else if (format == "but") {
      std::vector<std::string> skipped;
      setups = sim::read_but_reverbdb(args[0], &skipped);
      for (const std::string& s : skipped) log_warning("skipped " + s);
    } else if (format == "table") {
      setups = sim::read_setup_table(args[0]);
    } else {
      throw Error("--format must be r3vival, but or table, got '" + format + "'");
    }
    sim::RoomDrawOptions draw_options;
    const std::vector<double> range = parse_double_list(absorption_range, ',', "--absorption-range");
    if (range.size() != 2) throw Error("--absorption-range needs min,max");
    draw_options.absorption_min = range[0];
    draw_options.absorption_max = range[1];
    draw_options.draw = sim::parse_absorption_draw(draw);
    draw_options.scattering = scattering;
    draw_options.seed = static_cast<uint64_t>(static_cast<int64_t>(seed));
    const std::vector<sim::RoomSpec> rooms = sim::rooms_from_setups(setups, draw_options);

    std::string header = "# made by rir-room-list --format=" + format + " --absorption-range=" + absorption_range +
                         " --absorption-draw=" + draw + " --seed=" + std::to_string(seed) + " from " + args[0];
    // A newline in the input's name or an option would end the comment and leave a bad line.
    for (char& c : header) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    }
    AtomicTextFile out(args[1]);
    out.stream() << header << "\n";
    for (const sim::RoomSpec& r : rooms) out.stream() << sim::format_room_list_line(r) << "\n";
    out.commit();
    log_info("wrote " + std::to_string(rooms.size()) + " room-list lines");
    return 0;
  });
}
