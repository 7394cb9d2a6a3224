// SPDX-License-Identifier: MIT
// How robot software uses sewerplan as its replanner (docs/executor.md).
//
// The robot's own controller runs the actions; sewerplan plans, and replans when the controller
// reports trouble it could not clear. Here the "robot" is played by hand: it follows the plan
// until it meets an obstacle in the pipe it is inspecting, reports it, and follows the new plan.
//
//   replanner_example MAP MISSION
#include <iostream>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"

using namespace sewerplan;  // NOLINT: an example program

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: replanner_example MAP MISSION\n";
    return 2;
  }
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map(argv[1], diagnostics);
  if (!map.has_value()) return std::cerr << map.error().message << '\n', 1;
  Result<Mission> mission = read_mission(argv[2], *map, diagnostics);
  if (!mission.has_value()) return std::cerr << mission.error().message << '\n', 1;

  executor::Replanner replanner(*map, *mission);
  executor::PlanResponse plan = replanner.plan();
  std::cout << "plan (" << plan.fused.actions.size() << " actions, ends at " << plan.end << "):\n"
            << domain::format_plan(plan.plan, *map, replanner.mission());

  // The robot carries out the plan up to its first inspection, and meets an obstacle 2 m into the
  // pipe. It tells the replanner where it is and what it has done...
  domain::PlanReplay replay(*map, replanner.mission(), replanner.progress());
  for (const auto& step : plan.plan.steps) {
    if (const auto* inspect = std::get_if<domain::InspectPipe>(&step)) {
      auto progress = replay.progress();
      const Pipe& pipe = map->pipe(inspect->pipe);
      const double x = std::get<domain::InPipe>(progress.position).offset_m;
      const double towards = x < pipe.length_m / 2 ? 1.0 : -1.0;
      progress.position = domain::InPipe{inspect->pipe, x + towards * 2.0};
      (void)replanner.update(progress, towards > 0 ? 1 : 0);
      // ... and what its recovery could not clear.
      plan = replanner.report_failure({.kind = executor::Failure::Kind::kBlockage,
                                       .pipe = inspect->pipe,
                                       .offset_m = x + towards * 2.05});
      break;
    }
    if (!replay.apply(step).has_value()) return 1;
  }
  if (!executor::has_plan(plan.decision)) {
    std::cout << executor::to_string(plan.decision) << ": " << plan.reason << '\n';
    return 0;
  }
  std::cout << "\nafter \"" << plan.reason << "\", new plan (ends at " << plan.end << "):\n"
            << domain::format_plan(plan.plan, *map, replanner.mission());
  for (const auto& d : plan.newly_dropped) {
    std::cout << "dropped '" << replanner.mission().task(d.task).name << "': " << d.reason << '\n';
  }
  return 0;
}
