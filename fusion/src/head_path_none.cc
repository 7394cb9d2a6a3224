// SPDX-License-Identifier: MIT
// plan_head_path in a build without OMPL (SEWERPLAN_WITH_OMPL=OFF): no motion planning.
#include "head_path.h"

namespace sewerplan::fusion::detail {

bool head_path_available() { return false; }

Result<void> head_space_sanity(const HeadPathProblem&, const TurnPlannerOptions&) {
  return Error{ErrorCode::kUnsupportedFormat, "this build of sewerplan has no OMPL"};
}

Result<HeadPath> plan_head_path(const HeadPathProblem&, const TurnPlannerOptions&,
                                const StopCondition&) {
  return Error{ErrorCode::kUnsupportedFormat,
               "this build of sewerplan has no OMPL (built with SEWERPLAN_WITH_OMPL=OFF): it "
               "cannot plan manhole motions; the angle and step rules apply"};
}

}  // namespace sewerplan::fusion::detail
