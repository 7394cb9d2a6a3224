// SPDX-License-Identifier: MIT
// A robot action as one JSON object on one line, with object names, for the executor's event log
// (JSON lines).
//
// The object has the action's kind, its plan step (from 1, as the validator counts steps), every
// parameter of robot_action.h under its own name, and the map's and mission's names for the
// objects it refers to; slots are numbered from 1, as in the paper's plans:
//
//   {"kind":"pass_manhole","plan_step":6,"manhole":"M6","from_slot":3,"to_slot":4,
//    "from_pipe":"P5","to_pipe":"P6","turn_deg":90,"step_m":0,"manhole_diameter_m":1.5,
//    "duration_s":47}
//
//   log << write_action_json(action, map, mission) << '\n';
//
// Thread safety: A pure function: call it from any number of threads.
#pragma once

#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/fusion/robot_action.h"

namespace sewerplan::fusion {

// Precondition: the action was fused with this map and mission (its IDs are theirs; checked).
// Runtime: O(1).
std::string write_action_json(const RobotAction& action, const SewerMap& map,
                              const Mission& mission);

}  // namespace sewerplan::fusion
