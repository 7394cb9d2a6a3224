// SPDX-License-Identifier: MIT
// HeadPathPlanner: the seam through which ManholeTurnPlanner (manhole_turn_planner.h) gets the
// head's path through a manhole: the head's pose (x, y, heading) from a start to a goal in a
// passage's canonical frame (manhole_geometry.h), curvature-bounded and inside the free space.
//
// fusion declares it and never implements it: the implementation is OMPL's (Dubins space, RRT,
// a seeded sampler: sewerplan/motion/ompl_head_path_planner.h, the motion library, built with
// SEWERPLAN_WITH_OMPL), so that fusion, and every program that links it, neither links nor loads
// OMPL and Boost. The program that plans manhole motions passes one in: the `sewerplan` command
// gets it from the OMPL module (sewerplan/modules/ompl.h, loaded the first time it plans one); a
// test or an embedder links the motion library and passes an OmplHeadPathPlanner. Without one,
// planning a motion is an error (kUnsupportedFormat) saying it needs the OMPL motion planner.
//
//   const motion::OmplHeadPathPlanner ompl;
//   ManholeTurnPlanner planner(&ompl, robot_body(profile), profile);
//
// Thread safety: an implementation is immutable: plan() and check_space() may run on several
// threads at once, each call with objects of its own.
#pragma once

#include <cstdint>
#include <vector>

#include "sewerplan/core/result.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/manhole_geometry.h"

namespace sewerplan::fusion {

struct TurnPlannerOptions {
  std::uint32_t seed = 1;
  std::uint32_t max_iterations = 2000;  // RRT iterations before giving up
};

// The head's pose in a passage's canonical frame.
struct HeadPose {
  double x_m = 0;
  double y_m = 0;
  double heading_rad = 0;
};

struct HeadPath {
  bool found = false;
  std::vector<HeadPose> poses;  // start to goal, densely (at most 0.01 m apart)
  std::uint32_t iterations = 0;
};

struct HeadPathProblem {
  PassageGeometry geometry;
  HeadPose start;
  HeadPose goal;
  double turn_radius_m = 0.4;     // the paths' smallest radius of curvature
  double clearance_m = 0.1;       // the head's disk that must lie in the manhole
  double pipe_clearance_m = 0.1;  // ... and in the pipes
  double pipe_reach_m = 0.5;      // how far into the pipes the head may go
};

class HeadPathPlanner {
 public:
  virtual ~HeadPathPlanner() = default;

  // A path not found within options.max_iterations is a HeadPath with found = false, not an
  // error. Errors: kInvalidArgument for a failure other than "no solution" (an invalid start or
  // goal, which the caller checks first); kCancelled or kSearchLimit when `stop` (its cancel flag
  // and time limit) fires first: asked at every iteration besides the iteration count.
  virtual Result<HeadPath> plan(const HeadPathProblem& problem, const TurnPlannerOptions& options,
                                const StopCondition& stop) const = 0;

  // The sanity checks of the state space plan() sets up for `problem` (OMPL's sanityChecks()):
  // a failed check's message as kInvalidArgument.
  virtual Result<void> check_space(const HeadPathProblem& problem,
                                   const TurnPlannerOptions& options) const = 0;
};

}  // namespace sewerplan::fusion
