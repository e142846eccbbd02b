// Room lists: the input of rir-simulate, one RIR per line:
//   <rir-id> room=Lx,Ly,Lz src=x,y,z mic=x,y,z [key=value ...]
// Blank lines and '#' comments (whole line or trailing) are ignored. Every error names file:line.
// The full key reference is room_list_keys_help() (printed by rir-simulate --help).
#pragma once
#include <string>
#include <vector>

#include "sim/room.h"

namespace tsrir::sim {

// Defaults used where a line gives neither absorption nor t60 (or no scattering).
constexpr double kDefaultAbsorption = 0.2;
constexpr double kDefaultScattering = 0.1;

// Parses one non-comment line; `context` is "file:line" (stored in RoomSpec::where). The result
// has passed validate_room().
RoomSpec parse_room_list_line(const std::string& line, const std::string& context);

// Parses a whole list; `source` names it in messages. Duplicate rir ids are errors.
std::vector<RoomSpec> parse_room_list(const std::string& text, const std::string& source);
// Reads a file ("-" = stdin).
std::vector<RoomSpec> read_room_list(const std::string& path);

// One line that parse_room_list_line() reads back to the same RoomSpec (values printed with 9
// significant digits; per-surface absorption written only where surfaces differ).
std::string format_room_list_line(const RoomSpec& room);

// The key reference for --help texts.
std::string room_list_keys_help();

}  // namespace tsrir::sim
