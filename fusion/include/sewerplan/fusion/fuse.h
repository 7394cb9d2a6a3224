// SPDX-License-Identifier: MIT
// Plan fusion: a symbolic plan, the map and the mission's robot profile -> parameterised robot
// actions (robot_action.h), the MAKRO paper's "plan fusion" (Adria, Streich and Hertzberg 2004,
// section 4.6).
//
// fuse() replays the plan step by step with the validator's PlanReplay (domain/validator.h), so it
// knows the robot's exact position before every step, and turns each step into one action whose
// every parameter comes from the map and the profile: distances from pipe offsets, turns and steps
// from the slots' azimuths and inverts (core/map_queries.h), speeds and times from the profile.
// Durations are the costs of docs/domain.md, computed as the validator computes them, so a fused
// plan's total_duration_s() is the validator's total_cost_s. The executor runs the actions through
// their jobs (jobs.h).
//
//   Result<FusedPlan> fused = fuse(plan, map, mission, initial_progress(mission, map));
//   if (!fused.has_value()) std::cerr << fused.error() << '\n';
//   for (const RobotAction& action : fused->actions) run(expand(action, mission.profile));
//
// Heading. A robot cannot turn around in a pipe (core/robot_profile.h), so fusion tracks which
// end of its pipe the robot faces: after entering a pipe (ENTER_PIPE, DRIVE_MANHOLE) it faces the
// far end; forward is towards the end it faces, backward towards the end it came in by. A start in
// a pipe has no entry; by convention the robot then faces the pipe's ends[1] (downstream), unless
// FuseOptions::start_heading_end says otherwise (a replanning start, where the executor knows).
//
// Errors, each naming the step and the object:
// - kInvalidArgument: a step the validator refuses, with its message ("step 3
// (DRIVE_PIPE_TO_MANHOLE
//   P1 M3): the robot is at M2 slot 1 (P12), not in pipe P1"), or a start it refuses;
// - kInvalidMap: map data an action cannot use: a manhole narrower than a pipe opening into it, a
//   non-finite azimuth or invert, a non-positive pipe length or diameter. Never a default.
// - kInvalidProfile: the mission's profile fails validate_profile.
// The goal is not checked: a prefix of a plan fuses (the executor fuses what it will run).
//
// Thread safety: fuse is a pure function of its (const) arguments: call it from any number of
// threads.
#pragma once

#include <cstdint>

#include "sewerplan/core/mission.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/fusion/robot_action.h"

namespace sewerplan::fusion {

struct FuseOptions {
  // For a start in a pipe: the end (0 or 1) the robot faces. Ignored for other starts.
  std::uint8_t start_heading_end = 1;
};

// Runtime: O(steps x tasks), as the validator.
Result<FusedPlan> fuse(const domain::Plan& plan, const SewerMap& map, const Mission& mission,
                       const domain::MissionProgress& start, const FuseOptions& options = {});

}  // namespace sewerplan::fusion
