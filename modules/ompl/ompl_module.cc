// SPDX-License-Identifier: MIT
// The OMPL module's two exported symbols (sewerplan/modules/ompl_table.h, module.h): its ABI stamp
// and the table that gives the motion library's OmplHeadPathPlanner. Built into sewerplan_ompl.so
// with everything else, OMPL's users among it, hidden.
#include <string>

#include "sewerplan/modules/ompl_table.h"
#include "sewerplan/motion/ompl_head_path_planner.h"

namespace sewerplan::modules {
namespace {

const fusion::HeadPathPlanner* head_path_planner() {
  static const motion::OmplHeadPathPlanner planner;
  return &planner;
}

const OmplTable kTable{.head_path_planner = &head_path_planner};

}  // namespace
}  // namespace sewerplan::modules

extern "C" __attribute__((visibility("default"))) const char* sewerplan_ompl_module_stamp() {
  static const std::string stamp = sewerplan::modules::ompl_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_ompl_module() {
  return &sewerplan::modules::kTable;
}
