#include "diagnose/measured_set.h"

#include <set>

#include "io/rir_set.h"
#include "sim/room_list.h"
#include "util/error.h"

namespace tsrir::diagnose {

MeasuredSet load_measured_set(const std::string& room_list, const std::string& rir_scp) {
  MeasuredSet set;
  set.rooms = sim::read_room_list(room_list);
  std::set<std::string> ids;
  for (const sim::RoomSpec& r : set.rooms) ids.insert(r.rir_id);
  const std::vector<RirRef> refs = read_rir_refs(rir_scp, run_inputs());
  // All ids first: a list whose last id is unknown fails before reading thousands of WAVs.
  for (const RirRef& ref : refs) {
    if (!ids.count(ref.id)) {
      throw Error(ref.where + ": measured RIR '" + ref.id + "' has no line in the room list " + room_list);
    }
  }
  if (refs.size() < 6) {
    throw Error(rir_scp + ": " + std::to_string(refs.size()) + " RIRs; rir-diagnose decides over a set and needs at least 6");
  }
  for (const RirRef& ref : refs) {
    set.measured.push_back(load_rir(ref));
    set.where.push_back(ref.where + " (" + ref.rxfilename + ")");
  }
  return set;
}

}  // namespace tsrir::diagnose
