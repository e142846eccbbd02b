// Reading the inputs of rir-diagnose: a room list and the measured RIRs, matched by id.
#pragma once
#include <string>
#include <vector>

#include "io/signal.h"
#include "sim/room.h"

namespace tsrir::diagnose {

struct MeasuredSet {
  std::vector<sim::RoomSpec> rooms;   // all lines of the room list
  std::vector<Signal> measured;       // scp order, at their own rates
  std::vector<std::string> where;     // per measured RIR: "scp:line (file)", for messages
};

// Errors (naming the file and line): unreadable files, a measured id without a room-list line
// (checked for the whole list before any RIR is read), fewer than 6 RIRs.
MeasuredSet load_measured_set(const std::string& room_list, const std::string& rir_scp);

}  // namespace tsrir::diagnose
