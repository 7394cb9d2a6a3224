// SPDX-License-Identifier: MIT
#include "sewerplan/modules/ompl.h"

#include <string>

#if SEWERPLAN_WITH_OMPL
#include "sewerplan/modules/module.h"
#include "sewerplan/modules/ompl_table.h"
#endif

namespace sewerplan::modules {

Result<const fusion::HeadPathPlanner*> ompl_head_path_planner() {
#if SEWERPLAN_WITH_OMPL
  static const Result<const fusion::HeadPathPlanner*> planner =
      [](Result<const OmplTable*> loaded) -> Result<const fusion::HeadPathPlanner*> {
    if (loaded.has_value()) return (*loaded)->head_path_planner();
    return Error{loaded.error().code,
                 "sewerplan cannot plan manhole motions: they need OMPL, but " +
                     loaded.error().message + "; the angle and step rules apply"};
  }(load_module_table<OmplTable>(kOmplModule, ompl_stamp()));
  return planner;
#else
  return Error{ErrorCode::kUnsupportedFormat,
               "this build of sewerplan has no OMPL (built with SEWERPLAN_WITH_OMPL=OFF): it "
               "cannot plan manhole motions; the angle and step rules apply"};
#endif
}

}  // namespace sewerplan::modules
