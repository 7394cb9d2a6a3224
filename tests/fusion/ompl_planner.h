// SPDX-License-Identifier: MIT
// The head path planner the fusion tests inject (sewerplan/fusion/head_path_planner.h): the motion
// library's OmplHeadPathPlanner, linked, in a build with OMPL; none (null) without.
#pragma once

#include "sewerplan/fusion/head_path_planner.h"
#if SEWERPLAN_TEST_WITH_OMPL
#include "sewerplan/motion/ompl_head_path_planner.h"
#endif

namespace sewerplan::testing {

inline const fusion::HeadPathPlanner* ompl_planner() {
#if SEWERPLAN_TEST_WITH_OMPL
  static const motion::OmplHeadPathPlanner planner;
  return &planner;
#else
  return nullptr;
#endif
}

}  // namespace sewerplan::testing
