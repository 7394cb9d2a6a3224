// SPDX-License-Identifier: MIT
// plan_head_path and head_space_sanity through the OMPL module (ompl_module.h), loaded on the
// first call.
#include <string>

#include "sewerplan/core/module.h"

#include "head_path.h"
#include "ompl_module.h"

namespace sewerplan::fusion::detail {
namespace {

// The module's table, or why there is none in the words of head_path_support().
const Result<const OmplModuleTable*>& ompl_module() {
  static const Result<const OmplModuleTable*> table =
      [](Result<const OmplModuleTable*> loaded) -> Result<const OmplModuleTable*> {
    if (loaded.has_value()) return loaded;
    return Error{loaded.error().code,
                 "sewerplan cannot plan manhole motions: they need OMPL, but " +
                     loaded.error().message + "; the angle and step rules apply"};
  }(load_module_table<OmplModuleTable>(kOmplModuleName, ompl_module_stamp()));
  return table;
}

}  // namespace

Result<void> head_path_support() {
  if (!ompl_module().has_value()) return ompl_module().error();
  return {};
}

bool head_path_available() { return ompl_module().has_value(); }

Result<void> head_space_sanity(const HeadPathProblem& problem, const TurnPlannerOptions& options) {
  const Result<const OmplModuleTable*>& module = ompl_module();
  if (!module.has_value()) return module.error();
  return (*module)->head_space_sanity(problem, options);
}

Result<HeadPath> plan_head_path(const HeadPathProblem& problem, const TurnPlannerOptions& options,
                                const StopCondition& stop) {
  const Result<const OmplModuleTable*>& module = ompl_module();
  if (!module.has_value()) return module.error();
  return (*module)->plan_head_path(problem, options, stop);
}

}  // namespace sewerplan::fusion::detail
