// SPDX-License-Identifier: MIT
// Issue 14: a go-to at a pipe's very end (its offset equal to the pipe's length, or 0).
#include <gtest/gtest.h>

#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/ais_testbed.h"

namespace sewerplan::search {
namespace {

PipeId pipe_named(const SewerMap& map, std::string_view name) {
  for (PipeId p : map.pipe_ids()) {
    if (map.pipe(p).name == name) return p;
  }
  ADD_FAILURE() << "no pipe " << name;
  return PipeId{0};
}

// On the AIS map, a single go-to at P2 8.062 m (the pipe's M4 end) was answered "no plan does all
// 1 remaining tasks within the battery ... though each task alone is within reach".
TEST(PipeEndGoal, AGoToAtAPipesEndIsPlannedIssue14) {
  const auto ais = testing::load_ais_testbed();
  const PipeId p2 = pipe_named(ais.map, "P2");
  for (double offset : {ais.map.pipe(p2).length_m, 0.0, 4.0}) {
    for (bool select_goals : {false, true}) {
      for (Algorithm algorithm :
           {Algorithm::kAuto, Algorithm::kAstar, Algorithm::kGbfs, Algorithm::kExact}) {
        Mission mission = ais.mission;
        mission.tasks = {Task{.name = "to the end",
                              .kind = TaskKind::kGoTo,
                              .place = PipeSpot{.pipe = p2, .offset_m = offset}}};
        mission.exits.clear();
        for (ManholeId m : ais.map.manhole_ids()) {
          if (ais.map.manhole(m).exit) mission.exits.push_back(m);
        }
        const auto start = domain::initial_progress(mission, ais.map);
        auto outcome = plan_mission(ais.map, mission, start,
                                    {.algorithm = algorithm, .select_goals = select_goals});
        ASSERT_TRUE(outcome.has_value())
            << "offset " << offset << ", " << to_string(algorithm) << ": " << outcome.error();
        EXPECT_TRUE(outcome->dropped.empty());
        const auto report = domain::validate_plan(outcome->plan, ais.map, mission, start);
        EXPECT_TRUE(report.valid) << report.error;
      }
    }
  }
}

}  // namespace
}  // namespace sewerplan::search
