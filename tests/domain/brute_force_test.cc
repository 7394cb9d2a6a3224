// SPDX-License-Identifier: MIT
// The brute-force oracle of tests/support: on the AIS test bed and on small maps whose cheapest
// plan is worked out by hand.
#include "support/brute_force.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"

#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::testing {
namespace {

// The oracle's plan must be valid and cost what it claims, to the bit.
void expect_valid(const BruteForceOutcome& best, const SewerMap& map, const Mission& mission) {
  ASSERT_TRUE(best.has_value()) << to_string(best.status());
  const domain::ValidationReport report = domain::validate_plan(best->plan, map, mission);
  EXPECT_TRUE(report.valid) << report.error << "\n"
                            << domain::format_plan(best->plan, map, mission);
  EXPECT_EQ(report.total_cost_s, best->cost_s);
}

TEST(BruteForce, FindsAPlanAsCheapAsThePapersOnTheAisTestbed) {
  const AisTestbed ais = load_ais_testbed();
  const BruteForceOutcome best = brute_force_optimal_plan(ais.map, ais.mission);
  ASSERT_EQ(best.status(), BruteForceStatus::kFound);
  expect_valid(best, ais.map, ais.mission);
  Diagnostics d;
  Result<domain::Plan> paper =
      domain::parse_plan(kCorrectedPaperPlan, "p", ais.map, ais.mission, d);
  ASSERT_TRUE(paper.has_value());
  const double paper_cost = domain::validate_plan(*paper, ais.map, ais.mission).total_cost_s;
  EXPECT_NEAR(best->cost_s, paper_cost, 1e-9)
      << domain::format_plan(best->plan, ais.map, ais.mission);
  // It is the paper's route; the oracle names the inspection's finish manhole.
  std::string text = domain::format_plan(best->plan, ais.map, ais.mission);
  const std::string inspect = "INSPECT_PIPE P4 M5\n";
  ASSERT_NE(text.find(inspect), std::string::npos) << text;
  text.replace(text.find(inspect), inspect.size(), "INSPECT_PIPE P4\n");
  EXPECT_EQ(text, kCorrectedPaperPlan);
}

// M1 (0,0) -P1- M2 (10,0) -P3- M4 (10,10) -P4- M3 (0,10), and a diagonal P2 from M2 to M3 that
// turns 135 degrees in M2. The robot starts lowered into M1; M3 is the only exit.
SewerMap detour_map() {
  SmallMap drawing;
  drawing.manhole("M1", 0, 0).manhole("M2", 10, 0).manhole("M3", 0, 10, true).manhole("M4", 10, 10);
  drawing.pipe("P1", "M1", "M2")
      .pipe("P2", "M2", "M3")
      .pipe("P3", "M2", "M4")
      .pipe("P4", "M4", "M3");
  return drawing.build();
}

TEST(BruteForce, TakesTheDetourWhenTheDirectTurnIsTooSharp) {
  const SewerMap map = detour_map();
  const Mission mission = small_mission(map, "M1");
  const BruteForceOutcome best = brute_force_optimal_plan(map, mission);
  expect_valid(best, map, mission);
  // Enter P1 (20 s), drive 10 m, turn 90 in M2 (20 + 27 s), 10 m, 90 in M4 (47 s), 10 m.
  EXPECT_NEAR(best->cost_s, 20 + 3 * (10 / 0.3) + 2 * (20 + 90 * 0.3), 1e-9);
  EXPECT_EQ(best->plan.steps.size(), 6U);
}

TEST(BruteForce, TakesTheDiagonalWhenTheRobotMayTurnThatFar) {
  const SewerMap map = detour_map();
  Mission mission = small_mission(map, "M1");
  mission.profile.max_turn_deg = 140;
  const BruteForceOutcome best = brute_force_optimal_plan(map, mission);
  expect_valid(best, map, mission);
  // Enter P1 (20 s), drive 10 m, turn 135 in M2 (20 + 40.5 s), drive the 14.14 m diagonal.
  EXPECT_NEAR(best->cost_s, 20 + 10 / 0.3 + 20 + 135 * 0.3 + std::hypot(10.0, 10.0) / 0.3, 1e-9);
}

TEST(BruteForce, InspectsAPipeAndReturnsToTheExit) {
  SmallMap drawing;
  drawing.manhole("M1", 0, 0, true).manhole("M2", 10, 0).manhole("M3", 20, 0);
  drawing.pipe("P1", "M1", "M2").pipe("P2", "M2", "M3");
  const SewerMap map = drawing.build();
  Mission mission = small_mission(map, "P1");
  add_task(mission, map, "inspect", TaskKind::kInspectPipe, "P2");
  const BruteForceOutcome best = brute_force_optimal_plan(map, mission);
  expect_valid(best, map, mission);
  // 5 m to M2, straight into P2, 10 m scanned, 10 m back to M2, straight into P1, 10 m to M1.
  EXPECT_NEAR(best->cost_s, 5 / 0.3 + 20 + 10 / 0.1 + 10 / 0.3 + 20 + 10 / 0.3, 1e-9);
}

TEST(BruteForce, OrdersTasksByTheCheapestTour) {
  // A star: M0 in the middle, samples at the ends of three arms of 5, 10 and 15 m.
  SmallMap drawing;
  drawing.manhole("M0", 0, 0, true).manhole("A", 5, 0).manhole("B", 0, 10).manhole("C", -15, 0);
  drawing.pipe("PA", "M0", "A").pipe("PB", "M0", "B").pipe("PC", "M0", "C");
  const SewerMap map = drawing.build();
  Mission mission = small_mission(map, "M0");
  add_task(mission, map, "a", TaskKind::kTakeWaterSample, "PA", 5.0);
  add_task(mission, map, "b", TaskKind::kTakeWaterSample, "PB", 10.0);
  add_task(mission, map, "c", TaskKind::kGoTo, "PC", 15.0);
  const BruteForceOutcome best = brute_force_optimal_plan(map, mission);
  expect_valid(best, map, mission);
  // Each arm out and back (60 m in all), two samples, entering the first arm from M0 (20 s) and
  // two passes through M0 between arms. From A (east) to C (west) is straight; to or from B
  // (north) turns 90 degrees. The cheapest orders take A and C one after the other: passes of
  // 90 and 0 degrees. The last arm ends back at M0, the exit.
  const double expected = 20 + 60 / 0.3 + 2 * 180 + (20 + 90 * 0.3) + 20;
  EXPECT_NEAR(best->cost_s, expected, 1e-9);
}

TEST(BruteForce, SaysWhenNoPlanExists) {
  const SewerMap map = detour_map();
  Mission mission = small_mission(map, "M1");
  mission.closed_pipes.push_back(*map.find_pipe("P4"));
  const BruteForceOutcome none = brute_force_optimal_plan(map, mission);
  EXPECT_EQ(none.status(), BruteForceStatus::kNoPlan);
  EXPECT_FALSE(none.has_value());
  EXPECT_GT(none.states(), 1U);
}

TEST(BruteForce, SaysWhenTheBatteryRulesEveryPlanOut) {
  const SewerMap map = detour_map();
  Mission mission = small_mission(map, "M1");
  mission.profile.battery_wh = 5;  // 150 s; the detour takes 214 s
  EXPECT_EQ(brute_force_optimal_plan(map, mission).status(), BruteForceStatus::kNoPlan);
}

TEST(BruteForce, StopsAtTheStateLimit) {
  const AisTestbed ais = load_ais_testbed();
  const BruteForceOutcome capped = brute_force_optimal_plan(ais.map, ais.mission, 10);
  EXPECT_EQ(capped.status(), BruteForceStatus::kStateLimit);
  EXPECT_FALSE(capped.has_value());
}

TEST(BruteForce, IsDeterministic) {
  const AisTestbed ais = load_ais_testbed();
  const BruteForceOutcome a = brute_force_optimal_plan(ais.map, ais.mission);
  const BruteForceOutcome b = brute_force_optimal_plan(ais.map, ais.mission);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->plan, b->plan);
  EXPECT_EQ(a.states(), b.states());
}

}  // namespace
}  // namespace sewerplan::testing
