// SPDX-License-Identifier: MIT
// ManholeTurnPlanner: a collision-free motion of the whole body through a manhole, its head's path
// from an injected HeadPathPlanner (OMPL's: head_path_planner.h).
//
// Follow-the-leader (docs/motion.md): the head drives a path and every segment follows it, each
// joint on the path one segment length behind the one before. A path whose curvature radius is at
// least RobotBody::min_turn_radius_m() bends no joint more than its yaw limit, and every segment,
// a chord of the path, stays within RobotBody::bend_margin_m() of it. So the planner plans the
// head's pose (x, y, heading) in OMPL's Dubins space (Dubins 1957, "On curves of minimal length
// with a constraint on average curvature..."; forward-only, curvature-bounded paths) with RRT
// (LaValle 1998) and a goal bias, from 0.5 m inside the from-pipe to 0.5 m inside the to-pipe. A
// state is valid if the head's disk of half the body's width plus that margin lies in the manhole
// (half the width in a pipe) of the passage's free space (manhole_geometry.h). A step is climbed
// by lifting two segments (the paper, section 2.2): the step must be within
// RobotBody::max_climb_m(), and the path must run straight along the pipe's axis for the lifted
// segment's horizontal reach before the higher mouth. The planned path is then checked by moving
// the whole chain along it: every segment inside the free space, every joint within its yaw limit;
// if that fails, the head is planned once more with the manhole's margin in the pipes too.
//
// Deterministic: the sampler and RRT's goal bias have their own RNGs seeded with `seed`, the
// nearest-neighbour structure is linear, the planner stops after a fixed number of iterations (not
// a time), and the path is shortened greedily rather than by random shortcuts. The same geometry
// and seed give the same bits. A caller's deadline or cancel (the StopCondition of every
// sewerplan algorithm) does not change a plan: it ends the planning with an error instead. The
// head's path comes from a HeadPathPlanner the caller passes in (head_path_planner.h: OMPL's, in
// the motion library), so fusion neither links nor loads OMPL; without one, plan() fails with
// kUnsupportedFormat.
//
//   const motion::OmplHeadPathPlanner ompl;  // or the OMPL module's (sewerplan/modules/ompl.h)
//   ManholeTurnPlanner planner(&ompl, robot_body(profile), profile);
//   Result<TurnPlan> plan = planner.plan(passage_geometry(map, m, from, to));
//   if (plan.has_value() && plan->feasible) use(plan->waypoints, plan->duration_s);
//
// Thread safety: A ManholeTurnPlanner does not change after construction: plan() and
// check_state_space() may run on several threads at once, as the HeadPathPlanner's may (OMPL's:
// each call with OMPL objects of its own; they set OMPL's process-wide log level, which OMPL guards
// with a mutex).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sewerplan/core/job.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/head_path_planner.h"
#include "sewerplan/fusion/manhole_geometry.h"

namespace sewerplan::fusion {

// The result for one passage geometry, in its canonical frame (manhole_geometry.h): the head's
// path from the from-pipe's mouth until the tail has entered the to-pipe, every 0.1 m; z above
// the floor (the lower invert).
struct TurnPlan {
  bool feasible = false;
  double duration_s = 0;
  double path_length_m = 0;
  double heading_change_deg = 0;  // the head's total turning, left and right
  std::vector<Waypoint> waypoints;
  std::string reason;  // why not, when infeasible
  std::uint32_t iterations = 0;
  friend bool operator==(const TurnPlan&, const TurnPlan&) = default;
};

class ManholeTurnPlanner {
 public:
  // Times come from the profile: duration = path / manoeuvre_speed_mps + heading change x
  // turn_s_per_deg + |step| x step_s_per_m. `head_paths`: the planner of the head's path, not
  // owned (it must outlive this); null: plan() and check_state_space() are an error.
  ManholeTurnPlanner(const HeadPathPlanner* head_paths, RobotBody body, const RobotProfile& profile,
                     TurnPlannerOptions options = {});

  // An infeasible passage is a TurnPlan with a reason, not an error. Errors: kInvalidArgument for
  // a geometry with non-positive or non-finite sizes; kUnsupportedFormat without a
  // HeadPathPlanner; kCancelled or kSearchLimit when `stop` (its cancel flag or time limit,
  // core/stop_condition.h) fires first: OMPL's termination condition asks it at every RRT
  // iteration.
  Result<TurnPlan> plan(const PassageGeometry& geometry, const StopCondition& stop = {}) const;

  const RobotBody& body() const { return body_; }
  const HeadPathPlanner* head_paths() const { return head_paths_; }

  // Runs OMPL's sanityChecks() on the state space plan() would use for `geometry` (the Dubins
  // space with the seeded sampler): a failed check's message as kInvalidArgument;
  // kUnsupportedFormat without a HeadPathPlanner.
  Result<void> check_state_space(const PassageGeometry& geometry) const;

 private:
  const HeadPathPlanner* head_paths_;
  RobotBody body_;
  double speed_mps_;
  double turn_s_per_deg_;
  double step_s_per_m_;
  TurnPlannerOptions options_;
};

}  // namespace sewerplan::fusion
