// The rir-room-list program body: measured-RIR metadata (R3VIVAL, BUT ReverbDB or a table) -> a
// room list for rir-simulate with random absorption (room_metadata.h). Options register themselves.
#pragma once
#include <string>

#include "sim/room_metadata.h"
#include "util/options.h"

namespace tsrir::sim {

enum class MetadataFormat { kR3vival, kBut, kTable };

struct RoomListCommand {
  MetadataFormat format = MetadataFormat::kTable;
  std::string absorption_range = "0.1,0.6";  // "min,max"; RoomDrawOptions' min and max
  RoomDrawOptions draw;                      // draw, scattering and seed are registered directly
  // r3vival only
  std::string room = "9.7,5.5,2.7";          // Lx,Ly,Lz in metres
  double source_height_m = 1.35;
  double mic_height_m = 1.35;
  std::string conditions;                    // comma-separated
  std::string id_format;                     // "" = {s_source}, or r3vival_{condition}_{s_source} with conditions

  void Register(OptionsItf* opts);
};

// Reads `metadata`, draws the rooms and writes `room_list_out` ('-' = stdout) atomically, with a
// '#' header line naming the settings. Returns the number of room-list lines.
size_t run_rir_room_list(const RoomListCommand& command, const std::string& metadata, const std::string& room_list_out);

}  // namespace tsrir::sim
