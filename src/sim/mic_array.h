// Microphone array geometry files (room-list key array=FILE): the positions of an array's
// microphones as offsets from its centre (the line's mic=), in array order = channel order.
// '#' starts a comment; blank lines are ignored. The first line names the kind:
//   linear n=N spacing_m=D [azimuth_deg=A] [elevation_deg=E]
//       N microphones D metres apart on a line through the centre along the axis (A, E)
//       (default A = 0, E = 0: along +x), centred: offsets (k - (N-1)/2) D, k = 0..N-1
//   circular n=N radius_m=R [start_deg=S]
//       N microphones on a horizontal circle of radius R, microphone k at azimuth S + 360 k / N
//   arbitrary
//       followed by one offset "dx dy dz" (metres) per line, at least one
// Every error names the file and line.
#pragma once
#include <string>
#include <vector>

#include "sim/room.h"

namespace tsrir::sim {

// Offsets from the array centre, metres, in array order.
std::vector<Vec3> parse_array_geometry(const std::string& text, const std::string& source);
std::vector<Vec3> read_array_geometry(const std::string& path);

// The format above, for --help texts.
std::string array_geometry_help();

}  // namespace tsrir::sim
