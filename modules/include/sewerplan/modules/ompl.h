// SPDX-License-Identifier: MIT
// The OMPL motion planner for a program that plans manhole motions without linking OMPL: the OMPL
// module's OmplHeadPathPlanner (ompl_table.h), loaded on the first call. fusion takes it injected
// (sewerplan/fusion/head_path_planner.h); `sewerplan motion precompute` is its one caller in the
// command, so no other run of the command loads OMPL.
//
//   Result<const fusion::HeadPathPlanner*> ompl = ompl_head_path_planner();
//   if (!ompl.has_value()) return ompl.error();  // says why, and that the rules apply
//   fusion::PrecomputeOptions options{.head_paths = *ompl};
//
// Thread safety: load_module's (any thread); the planner's (head_path_planner.h).
#pragma once

#include "sewerplan/core/result.h"
#include "sewerplan/fusion/head_path_planner.h"

namespace sewerplan::modules {

// The planner, or kUnsupportedFormat saying why there is none (this build has no OMPL; the module
// missing, not loadable or of another build, in the loader's words) and that the angle and step
// rules apply.
Result<const fusion::HeadPathPlanner*> ompl_head_path_planner();

}  // namespace sewerplan::modules
