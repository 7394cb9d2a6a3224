// SPDX-License-Identifier: MIT
// plan_head_path: the OMPL adapter of manhole_turn_planner.h, private to fusion.
//
// The head's pose in a passage's canonical frame is planned in OMPL's Dubins space with RRT. OMPL
// lives in a module of its own (ompl_module.h, fusion/module/ompl_module.cc, the only file that
// includes it): head_path_module.cc loads it on the first call, and head_path_none.cc replaces
// that in a build without OMPL. Our types in, our types out.
#pragma once

#include <cstdint>
#include <vector>

#include "sewerplan/core/result.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/manhole_geometry.h"
#include "sewerplan/fusion/manhole_turn_planner.h"

namespace sewerplan::fusion::detail {

struct Pose2 {
  double x_m = 0;
  double y_m = 0;
  double heading_rad = 0;
};

struct HeadPath {
  bool found = false;
  std::vector<Pose2> poses;  // start to goal, densely (at most 0.01 m apart)
  std::uint32_t iterations = 0;
};

struct HeadPathProblem {
  PassageGeometry geometry;
  Pose2 start;
  Pose2 goal;
  double turn_radius_m = 0.4;     // the paths' smallest radius of curvature
  double clearance_m = 0.1;       // the head's disk that must lie in the manhole
  double pipe_clearance_m = 0.1;  // ... and in the pipes
  double pipe_reach_m = 0.5;      // how far into the pipes the head may go
};

// Whether head paths can be planned: this build has OMPL and its module loads (on the first call
// of any function here; sewerplan/core/module.h says where from). Otherwise kUnsupportedFormat,
// the message saying why (no OMPL in this build, or the loader's reason: the module missing, not
// loadable, or of another build) and that the angle and step rules apply.
Result<void> head_path_support();
bool head_path_available();  // head_path_support() holds

// OMPL's sanityChecks() of the space plan_head_path sets up (with its seeded sampler); the
// exception's message if one fails. head_path_support()'s error without OMPL.
Result<void> head_space_sanity(const HeadPathProblem& problem, const TurnPlannerOptions& options);

// head_path_support()'s error without OMPL; an OMPL failure other than "no solution" (an invalid
// start or goal, which the caller checks first) is kInvalidArgument. `stop` (its cancel flag and
// time limit) is OMPL's termination condition besides the iteration count, asked at every RRT
// iteration: when it fires first, kCancelled or kSearchLimit.
Result<HeadPath> plan_head_path(const HeadPathProblem& problem, const TurnPlannerOptions& options,
                                const StopCondition& stop = {});

}  // namespace sewerplan::fusion::detail
