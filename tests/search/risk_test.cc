// SPDX-License-Identifier: MIT
// Risk-aware planning (PlannerOptions::risk, domain::RiskCosts): a possible blockage is worth
// driving past on the way to the tasks, where a stop costs a detour, rather than on the way back to
// the exit, where it may leave no way out; the reported cost stays the true time.
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/route_risk.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/search/planner.h"

#include "support/small_map.h"

namespace sewerplan::search {
namespace {

using domain::initial_progress;
using testing::add_task;
using testing::small_mission;
using testing::SmallMap;

// S -- X -- E in a line, each stretch twice: a short pipe with roots (p = 0.1) and a safe one
// 30 m longer (100 s more at makro-1.1's 0.3 m/s). The task is at X; E is the exit.
struct TwoCorridors {
  SewerMap map = SmallMap()
                     .manhole("S", 0, 0)
                     .manhole("X", 10, 0)
                     .manhole("E", 20, 0, /*exit=*/true)
                     .pipe("OUT_RISKY", "S", "X", 0.5, 10.0)
                     .pipe("OUT_SAFE", "S", "X", 0.5, 40.0)
                     .pipe("BACK_RISKY", "X", "E", 0.5, 10.0)
                     .pipe("BACK_SAFE", "X", "E", 0.5, 40.0)
                     .build();
  Mission mission = make_mission(map);

  static Mission make_mission(const SewerMap& map) {
    Mission m = small_mission(map, "S");
    add_task(m, map, "at X", TaskKind::kGoTo, "X");
    for (const char* pipe : {"OUT_RISKY", "BACK_RISKY"}) {
      m.hazards.push_back(
          {.pipe = *map.find_pipe(pipe), .offset_m = 5, .probability = 0.1, .reason = "BBA roots"});
    }
    return m;
  }

  std::vector<std::string> pipes_driven(const domain::Plan& plan) const {
    std::vector<std::string> names;
    for (const domain::PlanStep& step : plan.steps) {
      if (const auto* d = std::get_if<domain::DrivePipeToManhole>(&step)) {
        names.push_back(map.pipe(d->pipe).name);
      }
    }
    return names;
  }
};

TEST(RiskAwarePlanning, BlindTakesTheShortPipesBothWays) {
  const TwoCorridors net;
  auto outcome = plan_mission(net.map, net.mission, initial_progress(net.mission, net.map), {});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  EXPECT_EQ(net.pipes_driven(outcome->plan), (std::vector<std::string>{"OUT_RISKY", "BACK_RISKY"}));
  EXPECT_EQ(outcome->risk_cost_s, 0);
}

TEST(RiskAwarePlanning, TakesTheRiskOnTheWayOutAndTheSafePipeBack) {
  const TwoCorridors net;
  // Out: 0.1 x 600 s = 60 s expected, less than the 100 s detour. Back: 0.1 x 3600 s = 360 s.
  const auto start = initial_progress(net.mission, net.map);
  auto outcome = plan_mission(net.map, net.mission, start, {.risk = domain::kDefaultRiskCosts});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  EXPECT_EQ(net.pipes_driven(outcome->plan), (std::vector<std::string>{"OUT_RISKY", "BACK_SAFE"}))
      << domain::format_plan(outcome->plan, net.map, net.mission);
  EXPECT_NEAR(outcome->risk_cost_s, 60, 0.01);
  EXPECT_TRUE(outcome->risk_note.empty());
  // The reported cost is the true time, without the expected cost of stops.
  const auto report = domain::validate_plan(outcome->plan, net.map, net.mission, start);
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_NEAR(report.total_cost_s, outcome->cost_s, 0.01);
  const domain::RouteRisk risk = domain::route_risk(outcome->plan, net.map, net.mission, start);
  ASSERT_EQ(risk.passed.size(), 1U);
  EXPECT_EQ(risk.passed[0].hazard, 0U);
  EXPECT_NEAR(risk.unobstructed, 0.9, 1e-12);
}

TEST(RiskAwarePlanning, HeavierRisksAreAvoidedBothWays) {
  TwoCorridors net;
  for (Hazard& h : net.mission.hazards) h.probability = 0.5;  // 300 s expected on the way out
  auto outcome = plan_mission(net.map, net.mission, initial_progress(net.mission, net.map),
                              {.risk = domain::kDefaultRiskCosts});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  EXPECT_EQ(net.pipes_driven(outcome->plan), (std::vector<std::string>{"OUT_SAFE", "BACK_SAFE"}));
  EXPECT_EQ(outcome->risk_cost_s, 0);
}

TEST(RiskAwarePlanning, TheOnlyWayBackIsTakenWhateverItsRisk) {
  TwoCorridors net;
  net.mission.closed_pipes.push_back(*net.map.find_pipe("BACK_SAFE"));
  for (Hazard& h : net.mission.hazards) h.probability = 0.9;
  auto outcome = plan_mission(net.map, net.mission, initial_progress(net.mission, net.map),
                              {.risk = domain::kDefaultRiskCosts});
  ASSERT_TRUE(outcome.has_value()) << outcome.error();
  EXPECT_EQ(net.pipes_driven(outcome->plan), (std::vector<std::string>{"OUT_SAFE", "BACK_RISKY"}));
}

TEST(RiskAwarePlanning, TheExpectedCostDoesNotTakeTheBattery) {
  TwoCorridors net;
  net.mission.closed_pipes.push_back(*net.map.find_pipe("BACK_SAFE"));
  for (Hazard& h : net.mission.hazards) h.probability = 1.0;  // 3600 s expected on the way back
  // A battery for 20 minutes, far less than the expected hour: the plan still goes the safe way
  // out and comes back the only way there is.
  net.mission.profile.battery_wh = net.mission.profile.energy_wh(1200);
  const auto start = initial_progress(net.mission, net.map);
  auto aware = plan_mission(net.map, net.mission, start,
                            {.select_goals = true, .risk = domain::kDefaultRiskCosts});
  ASSERT_TRUE(aware.has_value()) << aware.error();
  EXPECT_TRUE(aware->dropped.empty());
  EXPECT_TRUE(aware->risk_note.empty());
  EXPECT_EQ(net.pipes_driven(aware->plan), (std::vector<std::string>{"OUT_SAFE", "BACK_RISKY"}));
}

TEST(RiskAwarePlanning, NeverDropsATaskOrTheBatteryTheBlindPlanKeeps) {
  TwoCorridors net;
  net.mission.closed_pipes.push_back(*net.map.find_pipe("BACK_SAFE"));
  for (Hazard& h : net.mission.hazards) h.probability = 1.0;
  const auto start = initial_progress(net.mission, net.map);
  auto blind = plan_mission(net.map, net.mission, start, {.select_goals = true});
  ASSERT_TRUE(blind.has_value()) << blind.error();
  // A battery for the short way only: the safe way out (100 s longer) does not fit.
  net.mission.profile.battery_wh = net.mission.profile.energy_wh(blind->cost_s + 10);
  blind = plan_mission(net.map, net.mission, start, {.select_goals = true});
  auto aware = plan_mission(net.map, net.mission, start,
                            {.select_goals = true, .risk = domain::kDefaultRiskCosts});
  ASSERT_TRUE(blind.has_value()) << blind.error();
  ASSERT_TRUE(aware.has_value()) << aware.error();
  EXPECT_TRUE(blind->dropped.empty());
  EXPECT_TRUE(aware->dropped.empty());
  EXPECT_EQ(aware->plan, blind->plan);
  EXPECT_FALSE(aware->risk_note.empty());
  // Without goal selection the same: the blind plan rather than none.
  aware = plan_mission(net.map, net.mission, start, {.risk = domain::kDefaultRiskCosts});
  ASSERT_TRUE(aware.has_value()) << aware.error();
  EXPECT_EQ(aware->plan, blind->plan);
}

}  // namespace
}  // namespace sewerplan::search
