// SPDX-License-Identifier: MIT
// RouteRisk: the hazards a plan drives past, and the chance that none of them stops the robot.
//
// A hazard (Mission::hazards) is a place where an inspection finding may stop the robot, with a
// probability p (core/condition_risk.h). A plan's route passes it when a step drives the robot
// across its offset (a pipe drive, an inspection, a go-to or a sample in the pipe). Assuming the
// findings stop the robot independently, the run is unobstructed with probability prod(1 - p)
// over the hazards passed; `plan` prints this along with the plan (plan --risk expected).
//
//   RouteRisk r = route_risk(plan, map, mission, initial_progress(mission, map));
//   for (const HazardPassed& h : r.passed) std::cout << mission.hazards[h.hazard].reason;
//
// Thread safety: A pure function over plain values.
#pragma once

#include <cstddef>
#include <vector>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"

namespace sewerplan::domain {

struct HazardPassed {
  std::size_t hazard = 0;  // index into Mission::hazards
  std::size_t step = 0;    // the plan's step that passes it (from 0)
  friend bool operator==(const HazardPassed&, const HazardPassed&) = default;
};

struct RouteRisk {
  std::vector<HazardPassed> passed;  // in the order the plan passes them (again if passed again)
  double unobstructed = 1;           // prod(1 - p) over `passed`
  friend bool operator==(const RouteRisk&, const RouteRisk&) = default;
};

// Replays `plan` from `start` (validator.h) and collects the hazards each step drives across
// (strictly between its start and end offsets); stops at a step that cannot be executed.
// Runtime: O(steps x (tasks + hazards)).
RouteRisk route_risk(const Plan& plan, const SewerMap& map, const Mission& mission,
                     const MissionProgress& start);

}  // namespace sewerplan::domain
