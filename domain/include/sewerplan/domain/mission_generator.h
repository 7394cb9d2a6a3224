// SPDX-License-Identifier: MIT
// generate_mission: a seeded random mission on a map, for tests and benchmarks.
//
// The robot starts in an exit manhole (where it is lowered in); the tasks go to distinct pipes it
// can reach within its limits, chosen at random among the nearest ones so that the mission is
// local, as real inspection missions are: among the 2 x tasks + 10 nearest (at most
// `radius_pipes`, at most half of all reachable pipes when there are enough). The mix is about
// 25% inspections (the dearest tasks: a 100 m pipe takes MAKRO PLUS 500 s), 30% water samples
// at the pipe's middle and 45% go-to tasks; a 20-task mission on a generated network then takes
// MAKRO PLUS well under its usable battery. The mission ends at any of the map's exits. The same
// map, options and seed give the same mission.
//
//   Result<Mission> m = generate_mission(map, {.tasks = 10, .seed = 3});
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::domain {

struct MissionOptions {
  std::size_t tasks = 5;
  std::uint64_t seed = 1;
  std::string profile = "makro-plus";
  std::size_t radius_pipes = 400;  // an upper limit on the nearest pipes tasks are drawn from
  double battery_reserve = 0.2;
};

// kInvalidArgument if the map has no exit, the profile is unknown, or fewer pipes than tasks are
// reachable from every exit tried.
Result<Mission> generate_mission(const SewerMap& map, const MissionOptions& options);

}  // namespace sewerplan::domain
