// rir-room-list: room lists for rir-simulate from measured-RIR metadata, with random absorption.
#include <string>

#include "sim/room_list_program.h"
#include "util/cli.h"

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
    sim::RoomListCommand command;
    command.Register(&cli);
    const std::vector<std::string> args = cli.parse(argc, argv, 2, 2);
    const size_t lines = sim::run_rir_room_list(command, args[0], args[1]);
    log_info("wrote " + std::to_string(lines) + " room-list lines");
    return 0;
  });
}
