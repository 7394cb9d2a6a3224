// SPDX-License-Identifier: MIT
// The OMPL module: plan_head_path and head_space_sanity with OMPL (head_path.h), behind one table
// in a shared module (sewerplan_ompl.so, fusion/module/ompl_module.cc) that fusion loads with
// dlopen the first time a manhole motion is planned. OMPL brings Boost.Serialization,
// Boost.Filesystem, ODE and libccd: linked into fusion, every run of every program paid for
// mapping, relocating and initialising them, about half the instructions of `sewerplan --version`
// or of a 12-manhole `plan` (docs/benchmarks.md), though most never plan a motion. Behind the
// module only the runs that plan one load them (head_path_module.cc).
//
// A module of sewerplan (sewerplan/core/module.h), named "ompl": it exports
// sewerplan_ompl_module_stamp, its ABI stamp (ompl_module_stamp() below as built into it), and
// sewerplan_ompl_module, the table. Private to fusion: only head_path_module.cc and the module
// include it.
//
// Thread safety: the entry points are head_path.h's; each call has OMPL objects of its own.
#pragma once

#include <string>

#include "sewerplan/core/module.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/manhole_geometry.h"
#include "sewerplan/fusion/manhole_turn_planner.h"

#include "head_path.h"

namespace sewerplan::fusion::detail {

struct OmplModuleTable {
  // head_space_sanity (head_path.h).
  Result<void> (*head_space_sanity)(const HeadPathProblem& problem,
                                    const TurnPlannerOptions& options);
  // plan_head_path (head_path.h).
  Result<HeadPath> (*plan_head_path)(const HeadPathProblem& problem,
                                     const TurnPlannerOptions& options, const StopCondition& stop);
};

inline constexpr const char* kOmplModuleName = "ompl";

// This build's ABI stamp for the table: the size of every type crossing it
// (sewerplan/core/module.h). head_path.h is not a public header, so the build id does not hash
// it: its types are all here.
inline std::string ompl_module_stamp() {
  const ModuleType types[] = {
      {"OmplModuleTable", sizeof(OmplModuleTable)},
      {"HeadPathProblem", sizeof(HeadPathProblem)},
      {"PassageGeometry", sizeof(PassageGeometry)},
      {"Pose2", sizeof(Pose2)},
      {"HeadPath", sizeof(HeadPath)},
      {"TurnPlannerOptions", sizeof(TurnPlannerOptions)},
      {"StopCondition", sizeof(StopCondition)},
      {"Result<void>", sizeof(Result<void>)},
      {"Result<HeadPath>", sizeof(Result<HeadPath>)},
      {"Error", sizeof(Error)},
  };
  return module_abi_stamp(types);
}

}  // namespace sewerplan::fusion::detail
