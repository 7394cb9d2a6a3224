// SPDX-License-Identifier: MIT
// OmplHeadPathPlanner: fusion's HeadPathPlanner (sewerplan/fusion/head_path_planner.h) with OMPL.
//
// The head's pose (x, y, heading) is planned in OMPL's Dubins space (Dubins 1957; forward-only,
// curvature-bounded paths) with RRT (LaValle 1998) and a goal bias; the validity checker is a
// lambda over the passage's free space (fusion/manhole_geometry.h: in_free_space). Deterministic:
// the sampler and RRT's goal bias have RNGs of their own seeded with TurnPlannerOptions::seed, the
// nearest-neighbour structure is linear, RRT stops after max_iterations (not a time), and the path
// is shortened greedily from the start rather than by random shortcuts. OMPL's PlannerStatus is
// translated to our ErrorCode here; no OMPL type is in this header.
//
// The motion library (sewerplan::motion, motion/) holds it alone: built with SEWERPLAN_WITH_OMPL,
// it links OMPL with Boost.Serialization, ODE and libccd, which cost every run of a program that
// links them about 17 ms of CPU to load (docs/benchmarks.md). A program that plans manhole motions
// links it, or, as the `sewerplan` command does so that its other runs do not pay for OMPL, loads
// it through the OMPL module (sewerplan/modules/ompl.h, sewerplan_ompl.so).
//
//   const OmplHeadPathPlanner ompl;
//   fusion::ManholeTurnPlanner planner(&ompl, fusion::robot_body(profile), profile);
//
// Thread safety: stateless: plan() and check_space() may run on several threads at once, each
// call with OMPL objects of its own. They set OMPL's process-wide log level (OMPL guards it with a
// mutex); SEWERPLAN_OMPL_DEBUG in the environment makes plan() log at OMPL's debug level.
#pragma once

#include "sewerplan/core/result.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/head_path_planner.h"

namespace sewerplan::motion {

class OmplHeadPathPlanner final : public fusion::HeadPathPlanner {
 public:
  Result<fusion::HeadPath> plan(const fusion::HeadPathProblem& problem,
                                const fusion::TurnPlannerOptions& options,
                                const StopCondition& stop) const override;
  Result<void> check_space(const fusion::HeadPathProblem& problem,
                           const fusion::TurnPlannerOptions& options) const override;
};

}  // namespace sewerplan::motion
