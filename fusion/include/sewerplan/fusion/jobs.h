// SPDX-License-Identifier: MIT
// Job expansion: each parameterised robot action (robot_action.h) as the base machine's jobs
// (core/job.h), the commands a robot runs one at a time.
//
// The paper's base machine (Adria, Streich and Hertzberg 2004, sections 2.3 and 4.6) executes
// short manoeuvres; an action is a short sequence of them:
//   DriveToManhole  -> DriveForward or DriveBackward (speed, distance; also of 0 m: a robot
//                      right at the pipe's end drives onto the manhole's mouth)
//   PassManhole     -> TurnInManhole (slots, turn, step, manhole diameter, duration)
//   EnterPipe       -> EnterPipeFromManhole (slot, duration)
//   TakeWaterSample -> [drive to the spot], Stop, TakeSample (sample time)
//   InspectPipe     -> [drive to the start end], Scan (inspection speed, length, backward when
//                      the inspection finishes at the end the robot came in by)
//   GoToPoint       -> [drive to the point]
//   GoToManhole     -> nothing (the robot is there)
// Any other drive of distance 0 is left out, so an action may expand to no job at all.
//
//   for (const PlannedJob& j : expand_plan(fused, mission.profile)) {
//     robot.run(j.job);  // report progress per j.action_index (and plan_step of that action)
//   }
//
// Thread safety: Pure functions and plain values: call them from any number of threads.
#pragma once

#include <cstddef>
#include <ostream>
#include <vector>

#include "sewerplan/core/job.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/fusion/robot_action.h"

namespace sewerplan::fusion {

// The action's jobs, in order. A PassManhole's waypoints (the motion planned for the passage,
// docs/motion.md) go into its TurnInManhole; without a motion table they are empty and the
// controller turns with its own manoeuvre (core/job.h). Runtime: O(waypoints).
std::vector<Job> expand(const RobotAction& action, const RobotProfile& profile);

// One job of a fused plan, with where it comes from.
struct PlannedJob {
  std::size_t action_index = 0;  // in FusedPlan::actions
  std::size_t job_index = 0;     // in expand(actions[action_index], profile)
  Job job;
  friend bool operator==(const PlannedJob&, const PlannedJob&) = default;
};

// "action 3 job 1: DriveForward(0.30 m/s, 12.50 m)"
std::ostream& operator<<(std::ostream& os, const PlannedJob& job);

// Every job of every action, in order. Runtime: O(actions).
std::vector<PlannedJob> expand_plan(const FusedPlan& plan, const RobotProfile& profile);

}  // namespace sewerplan::fusion
