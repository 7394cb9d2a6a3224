// SPDX-License-Identifier: MIT
// A robot action as a line for people (logs, the CLI's live log): the objects by their names on
// the map and in the mission, numbers with a fixed precision (metres and speeds 2 decimals, times
// 1), as operator<< (robot_action.h) prints it with IDs.
//
//   log << describe(action, map, mission);
//   // DriveToManhole(pipe P12 -> manhole M2, forward 2.83 m at 0.30 m/s, type 2, pipe 0.60 m) [9.4
//   s]
//
// Thread-safety: a free function over values it only reads; reentrant.
#pragma once

#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/fusion/robot_action.h"

namespace sewerplan::fusion {

// An ID that is not on the map or in the mission is printed as operator<< prints it ("#11").
std::string describe(const RobotAction& action, const SewerMap& map, const Mission& mission);

}  // namespace sewerplan::fusion
