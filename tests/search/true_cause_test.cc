// SPDX-License-Identifier: MIT
// Issue 30: every failure named for its true cause. A task cut off by a blockage (an obstacle the
// robot met, a finding that closes part of a pipe) is named with that blockage before any search,
// with and without goal selection, instead of a search's "no plan ... within the battery ...,
// though each task alone is within reach". On the paper's test environment (datasets/ais-testbed).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_io.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/search/planner.h"

#include "support/paths.h"

namespace sewerplan::search {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

class TrueCause : public ::testing::TestWithParam<Algorithm> {
 protected:
  void SetUp() override {
    Diagnostics d;
    auto map = read_map(testing::dataset_path("ais-testbed/map.json"), d);
    ASSERT_TRUE(map.has_value());
    map_ = std::move(*map);
    auto mission = read_mission(testing::dataset_path("ais-testbed/missions/paper.json"), map_, d);
    ASSERT_TRUE(mission.has_value()) << mission.error();
    mission_ = std::move(*mission);
    // A battery far beyond any plan: the battery is never the cause here.
    mission_.profile.battery_wh = 100'000;
  }
  PipeId p(const char* name) const { return *map_.find_pipe(name); }
  Result<PlanOutcome> plan(bool select_goals) const {
    return plan_mission(map_, mission_, domain::initial_progress(mission_, map_),
                        {.algorithm = GetParam(), .select_goals = select_goals});
  }
  SewerMap map_;
  Mission mission_;
};

TEST_P(TrueCause, ABlockedInspectionIsNamedNotTheBatteryIssue30) {
  mission_.blockages = {{p("P4"), 4.0}};
  const Result<PlanOutcome> outcome = plan(false);
  ASSERT_FALSE(outcome.has_value());
  EXPECT_EQ(outcome.error().code, ErrorCode::kNoPlan);
  EXPECT_THAT(outcome.error().message,
              HasSubstr("task 'inspect' (inspect_pipe): no position the robot can reach lets it "
                        "do the task: pipe P4 is blocked at 4.00 m"));
  EXPECT_THAT(outcome.error().message, Not(HasSubstr("within the battery")));
}

TEST_P(TrueCause, ASampleCutOffOnBothSidesIsNamedNotTheBatteryIssue30) {
  // W1 lies at 3 m in P6: blocked at 2 m and at 4 m, its pipe's ends are reachable, it is not.
  mission_.blockages = {{p("P6"), 2.0}, {p("P6"), 4.0}};
  const Result<PlanOutcome> outcome = plan(false);
  ASSERT_FALSE(outcome.has_value());
  EXPECT_THAT(outcome.error().message,
              HasSubstr("task 'sample' (take_water_sample): no position the robot can reach lets "
                        "it do the task: pipe P6 is blocked at 2.00 m"));
  EXPECT_THAT(outcome.error().message, Not(HasSubstr("within the battery")));
}

TEST_P(TrueCause, WithGoalSelectionTheCutOffTaskIsDroppedWithItsCause) {
  mission_.blockages = {{p("P6"), 2.0}, {p("P6"), 4.0}};
  const Result<PlanOutcome> outcome = plan(true);
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  ASSERT_EQ(outcome->dropped.size(), 1U);
  EXPECT_EQ(mission_.task(outcome->dropped[0].task).name, "sample");
  EXPECT_THAT(outcome->dropped[0].reason, HasSubstr("pipe P6 is blocked at 2.00 m"));
}

TEST_P(TrueCause, ACutOffEndPointIsNamedWithGoalSelection) {
  // The mission's end point moved to 2 m into P9, between two blockages: the pipe's ends are
  // reachable, the end point is not.
  mission_.tasks.back().place = PipeSpot{p("P9"), 2.0, {}};
  mission_.blockages = {{p("P9"), 1.0}, {p("P9"), 3.0}};
  const Result<PlanOutcome> outcome = plan(true);
  ASSERT_FALSE(outcome.has_value());
  EXPECT_THAT(outcome.error().message,
              HasSubstr("the final task 'end' (go_to): no position the robot can reach lets it do "
                        "the task: pipe P9 is blocked at 1.00 m"));
}

TEST(TrueCauseFromHere, NoRouteFromHereWhenTheRobotIsNotAtTheStartIssue30) {
  Diagnostics d;
  auto map = read_map(testing::dataset_path("ais-testbed/map.json"), d);
  ASSERT_TRUE(map.has_value());
  auto mission = read_mission(testing::dataset_path("ais-testbed/missions/paper.json"), *map, d);
  ASSERT_TRUE(mission.has_value());
  // The robot has driven to P4 and is shut in there, P4 blocked on both sides of it.
  mission->tasks.clear();
  domain::MissionProgress progress = domain::initial_progress(*mission, *map);
  progress.position = domain::InPipe{*map->find_pipe("P4"), 4.0};
  progress.energy_used_wh = 5;
  mission->blockages = {{*map->find_pipe("P4"), 3.0}, {*map->find_pipe("P4"), 5.0}};
  const Result<PlanOutcome> outcome = plan_mission(*map, *mission, progress, {});
  ASSERT_FALSE(outcome.has_value());
  EXPECT_THAT(outcome.error().message, HasSubstr("can be reached from here (in pipe P4 at 4 m)"));
  EXPECT_THAT(outcome.error().message, Not(HasSubstr("from the start")));
}

INSTANTIATE_TEST_SUITE_P(EveryAlgorithm, TrueCause,
                         ::testing::Values(Algorithm::kAuto, Algorithm::kAstar,
                                           Algorithm::kWeightedAstar, Algorithm::kGbfs,
                                           Algorithm::kEhc, Algorithm::kExact));

}  // namespace
}  // namespace sewerplan::search
