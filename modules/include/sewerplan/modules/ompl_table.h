// SPDX-License-Identifier: MIT
// The OMPL module: the motion library's OmplHeadPathPlanner (sewerplan/motion/
// ompl_head_path_planner.h) behind one table in a shared module (sewerplan_ompl.so,
// modules/ompl/ompl_module.cc) that the command loads with dlopen the first time it plans a
// manhole motion (sewerplan/modules/ompl.h: `motion precompute`). OMPL brings
// Boost.Serialization, Boost.Filesystem, ODE and libccd: linked into the command, every run paid
// for mapping, relocating and initialising them, about half the instructions of `sewerplan
// --version` or of a 12-manhole `plan` (docs/benchmarks.md), though only one command plans a
// motion.
//
// A module of sewerplan (module.h), named "ompl": it exports sewerplan_ompl_module_stamp, its ABI
// stamp (ompl_stamp() below as built into it), and sewerplan_ompl_module, the table. The planner
// it gives is an object of the module: its virtual functions are the module's code, and the module
// is never unloaded.
//
// Thread safety: the planner's (head_path_planner.h): any thread, each call with OMPL objects of
// its own.
#pragma once

#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/core/stop_condition.h"
#include "sewerplan/fusion/head_path_planner.h"
#include "sewerplan/fusion/manhole_geometry.h"
#include "sewerplan/modules/module.h"

namespace sewerplan::modules {

struct OmplTable {
  // The module's OmplHeadPathPlanner, alive as long as the process.
  const fusion::HeadPathPlanner* (*head_path_planner)();
};

inline constexpr const char* kOmplModule = "ompl";

// This build's ABI stamp for the table: the size of every type crossing it (module.h). The
// planner's virtual functions cross it too: their layout is head_path_planner.h's, which the build
// id covers.
inline std::string ompl_stamp() {
  const ModuleType types[] = {
      {"OmplTable", sizeof(OmplTable)},
      {"HeadPathPlanner", sizeof(fusion::HeadPathPlanner)},
      {"HeadPathProblem", sizeof(fusion::HeadPathProblem)},
      {"PassageGeometry", sizeof(fusion::PassageGeometry)},
      {"HeadPose", sizeof(fusion::HeadPose)},
      {"HeadPath", sizeof(fusion::HeadPath)},
      {"TurnPlannerOptions", sizeof(fusion::TurnPlannerOptions)},
      {"StopCondition", sizeof(StopCondition)},
      {"Result<void>", sizeof(Result<void>)},
      {"Result<HeadPath>", sizeof(Result<fusion::HeadPath>)},
      {"Error", sizeof(Error)},
  };
  return module_abi_stamp(types);
}

}  // namespace sewerplan::modules
