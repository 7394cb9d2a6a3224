// SPDX-License-Identifier: MIT
// plan_head_path in a build without OMPL (SEWERPLAN_WITH_OMPL=OFF): no motion planning.
#include "head_path.h"

namespace sewerplan::fusion::detail {

Result<void> head_path_support() {
  return Error{ErrorCode::kUnsupportedFormat,
               "this build of sewerplan has no OMPL (built with SEWERPLAN_WITH_OMPL=OFF): it "
               "cannot plan manhole motions; the angle and step rules apply"};
}

bool head_path_available() { return false; }

Result<void> head_space_sanity(const HeadPathProblem&, const TurnPlannerOptions&) {
  return head_path_support().error();
}

Result<HeadPath> plan_head_path(const HeadPathProblem&, const TurnPlannerOptions&,
                                const StopCondition&) {
  return head_path_support().error();
}

}  // namespace sewerplan::fusion::detail
