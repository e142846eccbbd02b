#include "diagnose/observations.h"

#include <cstdio>

#include "util/rng.h"
#include "util/strings.h"

namespace tsrir::diagnose {

RirFeatures RirObservation::features_of(const Signal& rir) const {
  return compute_features(rir, schroeder_hz);
}

SetObservations SetObservations::subset(const std::vector<size_t>& idx) const {
  SetObservations s;
  s.model_by_room = model_by_room;
  for (size_t i : idx) s.rirs.push_back(rirs.at(i));
  return s;
}

std::string room_group(const sim::RoomSpec& room) {
  if (!room.room_id.empty()) return room.room_id;
  std::string acoustic;
  for (const auto& surface : room.absorption) {
    for (double a : surface) acoustic += format_double(a, 6) + ",";
  }
  for (double s : room.scattering) acoustic += format_double(s, 6) + ",";
  char hash[16];
  std::snprintf(hash, sizeof hash, "%06llx", static_cast<unsigned long long>(stable_hash(acoustic) & 0xffffff));
  return "room" + format_double(room.size_m[0], 4) + "x" + format_double(room.size_m[1], 4) + "x" +
         format_double(room.size_m[2], 4) + "-" + hash;
}

}  // namespace tsrir::diagnose
