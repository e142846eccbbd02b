// Room lists from measured-RIR metadata (rir-room-list): each real RIR's room size and source /
// microphone positions become one room-list line, with random surface absorption drawn per RIR
// as the TS-RIR paper does (it had no material data either). Draws are keyed by (seed, rir id):
// the same RIR gets the same absorption whatever else is in the list.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sim/room.h"
#include "util/options.h"

namespace tsrir::sim {

struct MetadataSetup {
  std::string rir_id;
  std::string room_id;
  Vec3 size_m{0.0, 0.0, 0.0};
  Vec3 source_m{0.0, 0.0, 0.0};
  Vec3 mic_m{0.0, 0.0, 0.0};
  std::string where;   // file (and line) it came from
};

// R3VIVAL positions CSV (source_id,azimuth_deg,distance_m,x_m_approx,y_m_approx,source_type; the
// row whose source_type is "receiver" is the microphone). Heights are not published: the given
// source and mic heights are used. One setup per (condition, source); with no conditions, one per
// source. rir id = id_format with {condition}, {source} (as in the CSV) and {s_source} (the
// source with a leading 'S' when it lacks one, as in the R3VIVAL file names) replaced.
struct R3vivalOptions {
  Vec3 room_m{9.7, 5.5, 2.7};
  double source_height_m = 1.35;
  double mic_height_m = 1.35;
  std::vector<std::string> conditions;   // e.g. 000,025,050,075,100
  std::string id_format = "{s_source}";  // with conditions, e.g. "r3vival_{condition}_{s_source}"
};
std::vector<MetadataSetup> read_r3vival_positions(const std::string& csv_path, const R3vivalOptions& options);

// BUT ReverbDB (release rel_19_06 layout): <root>/<room>/env_meta.txt ($EnvDepth, $EnvWidth,
// $EnvHeight), <root>/<room>/<config>/<speaker>/spk_meta.txt ($EnvSpk1Depth/Width/Height) and
// <root>/<room>/<config>/<speaker>/<mic>/mic_meta.txt ($EnvMicID = N, $EnvMicNDepth/Width/Height);
// lines are "$Key<TAB>value". x = depth, y = width, z = height. rir id = room_config_speaker_mic,
// room id = room. Setups whose source or mic lies outside the stated room (the metadata has a
// few) are reported in *skipped ("file: reason") and left out.
std::vector<MetadataSetup> read_but_reverbdb(const std::string& root, std::vector<std::string>* skipped);

// A whitespace table with a header line naming at least the columns rir-id Lx Ly Lz sx sy sz mx my
// mz (any order; optional room-id). '#' comments and blank lines allowed.
std::vector<MetadataSetup> read_setup_table(const std::string& path);

enum class AbsorptionDraw { kPerRir, kPerSurface, kPerSurfaceBand };
const Choices<AbsorptionDraw>& absorption_draw_choices();  // "rir" | "surface" | "surface-band"

struct RoomDrawOptions {
  double absorption_min = 0.1;   // uniform draw in [min, max], within (0, 1]
  double absorption_max = 0.6;
  AbsorptionDraw draw = AbsorptionDraw::kPerSurface;
  double scattering = 0.1;
  uint64_t seed = 0;
};

// Turns setups into validated RoomSpecs with drawn absorption. Throws Error naming the setup's
// origin for invalid geometry, or for a bad range.
std::vector<RoomSpec> rooms_from_setups(const std::vector<MetadataSetup>& setups, const RoomDrawOptions& options);

}  // namespace tsrir::sim
