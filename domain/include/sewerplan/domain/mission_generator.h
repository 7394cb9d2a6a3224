// SPDX-License-Identifier: MIT
// generate_mission: a seeded random mission on a map, for tests and benchmarks.
//
// The robot starts in an exit manhole (where it is lowered in); the tasks go to distinct pipes it
// can reach within its limits, drawn in one of three shapes (MissionSpread):
//   - uniform: uniformly over every pipe it can drive to and back from on half its usable
//     battery, so each task alone fits the battery and the tasks lie all over the robot's range
//     (on a city, the whole network within a few kilometres): the hard case for a planner, whose
//     shortest-path searches must then cover the range;
//   - clustered: around a random centre within that range, among the 2 x tasks + 10 pipes nearest
//     to it (a street's worth of work far from the start);
//   - near-exit: among the 2 x tasks + 10 pipes nearest the start (at most `radius_pipes`, at most
//     half of all reachable pipes when there are enough), local as many real missions are.
// The mix is about
// 25% inspections (the dearest tasks: a 100 m pipe takes MAKRO PLUS 500 s), 30% water samples
// at the pipe's middle and 45% go-to tasks; a 20-task mission on a generated network then takes
// MAKRO PLUS well under its usable battery. The mission ends at any of the map's exits. The same
// map, options and seed give the same mission.
//
//   Result<Mission> m = generate_mission(map, {.tasks = 10, .seed = 3});
//
// Thread-safety: reentrant (it only reads the map; the seed is its only randomness).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::domain {

enum class MissionSpread { kUniform, kClustered, kNearExit };

std::string_view to_string(MissionSpread spread);
// uniform, clustered, near-exit
std::optional<MissionSpread> mission_spread_from_string(std::string_view name);
// The names mission_spread_from_string reads, "uniform, clustered, near-exit", for messages.
std::string mission_spread_names();

struct MissionOptions {
  std::size_t tasks = 5;
  std::uint64_t seed = 1;
  std::string profile = "makro-plus";
  std::size_t radius_pipes = 400;  // an upper limit on the nearest pipes tasks are drawn from
  double battery_reserve = 0.2;
  // The library's default keeps the missions tests were written against; the command line and the
  // planning benchmarks default to kUniform.
  MissionSpread spread = MissionSpread::kNearExit;
  // The profile's battery replaced (a larger or a tethered robot, up to 1e6 Wh): with one large
  // enough, the uniform spread draws from every pipe the robot can reach (issue 35's benchmarks).
  std::optional<double> battery_wh;
};

// kInvalidArgument if the map has no exit, the profile is unknown, or fewer pipes than tasks are
// reachable from every exit tried.
Result<Mission> generate_mission(const SewerMap& map, const MissionOptions& options);

}  // namespace sewerplan::domain
