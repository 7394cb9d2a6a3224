// SPDX-License-Identifier: MIT
// Goal selection (PlannerOptions::select_goals) and blockages: a mission that cannot be done in
// full still gets the plan that does the most tasks and ends the mission; a robot in a blocked
// pipe leaves on its own side.
#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::search {
namespace {

using domain::initial_progress;
using domain::MissionProgress;
using testing::add_task;
using testing::small_mission;
using testing::SmallMap;

// The plan must be valid for the tasks it keeps: dropped tasks count as not required.
void expect_valid_without(const SewerMap& map, const Mission& mission, MissionProgress start,
                          const PlanOutcome& outcome) {
  for (const auto& d : outcome.dropped) start.done[d.task.index()] = true;
  const auto report = domain::validate_plan(outcome.plan, map, mission, start);
  EXPECT_TRUE(report.valid) << report.error << "\n"
                            << domain::format_plan(outcome.plan, map, mission);
  EXPECT_NEAR(report.total_cost_s, outcome.cost_s, 0.01);  // costs are whole ms per action
}

TEST(GoalSelection, AClosedTaskPipeIsDroppedWithItsReasonAndTheRestDone) {
  testing::AisTestbed ais = testing::load_ais_testbed();
  ais.mission.closed_pipes.push_back(*ais.map.find_pipe("P4"));  // the inspection's pipe
  const auto start = initial_progress(ais.mission, ais.map);
  EXPECT_FALSE(plan_mission(ais.map, ais.mission, start, {}).has_value());
  auto outcome = plan_mission(ais.map, ais.mission, start, {.select_goals = true});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  ASSERT_EQ(outcome->dropped.size(), 1U);
  EXPECT_EQ(ais.mission.task(outcome->dropped[0].task).name, "inspect");
  EXPECT_NE(outcome->dropped[0].reason.find("pipe P4 is closed"), std::string::npos)
      << outcome->dropped[0].reason;
  expect_valid_without(ais.map, ais.mission, start, *outcome);
}

TEST(GoalSelection, AFeasibleMissionKeepsEveryTaskAndTheSamePlan) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  const auto start = initial_progress(ais.mission, ais.map);
  auto full = plan_mission(ais.map, ais.mission, start, {});
  auto selected = plan_mission(ais.map, ais.mission, start, {.select_goals = true});
  ASSERT_TRUE(full.has_value() && selected.has_value());
  EXPECT_TRUE(selected->dropped.empty());
  EXPECT_EQ(selected->plan, full->plan);
  EXPECT_DOUBLE_EQ(selected->cost_s, full->cost_s);
}

// A line of pipes from the exit A; tasks farther out cost more. With a battery for only some of
// them, the plan does as many as fit and returns to the exit; the brute force over subsets agrees
// on how many that is.
TEST(GoalSelection, TheBatteryDecidesHowManyTasksAndTheMostAreDone) {
  const SewerMap map = SmallMap()
                           .manhole("A", 0, 0, true)
                           .manhole("B", 20, 0)
                           .manhole("C", 40, 0)
                           .manhole("D", 60, 0)
                           .manhole("E", 0, 30)
                           .pipe("P1", "A", "B")
                           .pipe("P2", "B", "C")
                           .pipe("P3", "C", "D")
                           .pipe("P4", "A", "E")
                           .build();
  Mission mission = small_mission(map, "A");
  add_task(mission, map, "near", TaskKind::kTakeWaterSample, "P1", 10.0);
  add_task(mission, map, "middle", TaskKind::kTakeWaterSample, "P2", 10.0);
  add_task(mission, map, "far", TaskKind::kTakeWaterSample, "P3", 10.0);
  add_task(mission, map, "other", TaskKind::kTakeWaterSample, "P4", 15.0);
  const auto start = initial_progress(mission, map);
  for (double battery_wh : {60.0, 45.0, 30.0, 20.0, 12.0}) {
    mission.profile.battery_wh = battery_wh;
    auto outcome = plan_mission(map, mission, start, {.select_goals = true});
    ASSERT_TRUE(outcome.has_value()) << battery_wh << " Wh: " << outcome.error();
    expect_valid_without(map, mission, start, *outcome);
    // The most tasks any subset can do within the battery.
    std::size_t best = 0;
    for (unsigned subset = 0; subset < 16; ++subset) {
      MissionProgress only = start;
      std::size_t count = 0;
      for (std::size_t t = 0; t < 4; ++t) {
        only.done[t] = (subset & (1U << t)) == 0;
        count += only.done[t] ? 0U : 1U;
      }
      if (count > best && plan_mission(map, mission, only, {}).has_value()) best = count;
    }
    EXPECT_EQ(4 - outcome->dropped.size(), best) << battery_wh << " Wh";
    for (const auto& d : outcome->dropped) {
      EXPECT_TRUE(d.reason.find("battery") != std::string::npos ||
                  d.reason.find(" Wh are available") != std::string::npos)
          << d.reason;
    }
  }
}

TEST(GoalSelection, NoExitInReachIsStillNoPlan) {
  testing::AisTestbed ais = testing::load_ais_testbed();
  Mission& m = ais.mission;
  m.tasks.pop_back();  // no final task: the mission ends at an exit
  for (const char* p :
       {"P12", "P1", "P2", "P3", "P4", "P5", "P6", "P7", "P8", "P9", "P10", "P11", "P13", "P14"}) {
    m.closed_pipes.push_back(*ais.map.find_pipe(p));
  }
  // In P5, between M3 and M6 (no exits), with every pipe closed: the robot can leave P5 only.
  MissionProgress start = initial_progress(m, ais.map);
  start.position = domain::InPipe{*ais.map.find_pipe("P5"), 5.0};
  auto outcome = plan_mission(ais.map, m, start, {.select_goals = true});
  ASSERT_FALSE(outcome.has_value()) << domain::format_plan(outcome->plan, ais.map, m);
  EXPECT_EQ(outcome.error().code, ErrorCode::kNoPlan);
  EXPECT_NE(outcome.error().message.find("no exit"), std::string::npos) << outcome.error();
}

// The robot met an obstacle in P5 (M3 -> M6) and stands before it: it must leave through M3, and
// the sample in P6 and the inspection of P4 are then out of reach (MAKRO cannot turn from P3 into
// P4 at M5); it ends the mission at an exit.
TEST(Blockages, TheRobotLeavesABlockedPipeOnItsOwnSide) {
  testing::AisTestbed ais = testing::load_ais_testbed();
  ais.mission.tasks.pop_back();  // the end in P9 is out of reach too: end at an exit
  const PipeId p5 = *ais.map.find_pipe("P5");
  const Pipe& pipe = ais.map.pipe(p5);
  const bool from_m3 = ais.map.manhole(*pipe.ends[0].manhole).name == "M3";
  const double blocked_at = from_m3 ? 6.0 : pipe.length_m - 6.0;
  const double robot_at = from_m3 ? 5.9 : pipe.length_m - 5.9;
  ais.mission.blockages.push_back({p5, blocked_at});
  MissionProgress start = initial_progress(ais.mission, ais.map);
  start.position = domain::InPipe{p5, robot_at};
  auto outcome = plan_mission(ais.map, ais.mission, start, {.select_goals = true});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  const auto& first = std::get<domain::DrivePipeToManhole>(outcome->plan.steps.front());
  EXPECT_EQ(ais.map.manhole(first.manhole).name, "M3");
  EXPECT_EQ(outcome->dropped.size(), 2U);
  expect_valid_without(ais.map, ais.mission, start, *outcome);
  // Driving on through the obstacle is refused by the validator.
  domain::Plan through{{domain::DrivePipeToManhole{p5, *ais.map.find_manhole("M6")}}};
  const auto report = domain::validate_plan(through, ais.map, ais.mission, start);
  EXPECT_NE(report.error.find("pipe P5 is blocked at 6.00 m"), std::string::npos) << report.error;
}

TEST(Blockages, AnInspectionOfABlockedPipeIsDroppedWithTheReason) {
  testing::AisTestbed ais = testing::load_ais_testbed();
  const PipeId p4 = *ais.map.find_pipe("P4");
  ais.mission.blockages.push_back({p4, 3.0});
  const auto start = initial_progress(ais.mission, ais.map);
  auto outcome = plan_mission(ais.map, ais.mission, start, {.select_goals = true});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  ASSERT_EQ(outcome->dropped.size(), 1U);
  EXPECT_NE(outcome->dropped[0].reason.find("pipe P4 is blocked at 3.00 m"), std::string::npos)
      << outcome->dropped[0].reason;
}

}  // namespace
}  // namespace sewerplan::search
