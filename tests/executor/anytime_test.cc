// SPDX-License-Identifier: MIT
// Issue 14, "anytime with a safe first answer": when a replan runs out of time (or is cancelled),
// the answer is the rest of the current plan if it still holds, else the nearest reachable exit.
// On the paper's test environment (datasets/ais-testbed), whose plan is the paper's route
// P12 M2 P1 M3 P5 M6 P6 M6 P4 M5 P8 M9; the robot has driven its first three steps (to M3).
#include <atomic>
#include <string_view>

#include <gtest/gtest.h>

#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

using Decision = PlanResponse::Decision;

PipeId pipe_named(const SewerMap& map, std::string_view name) {
  for (PipeId p : map.pipe_ids()) {
    if (map.pipe(p).name == name) return p;
  }
  ADD_FAILURE() << "no pipe " << name;
  return PipeId{0};
}

class AnytimeReplan : public ::testing::Test {
 protected:
  void SetUp() override {
    first_ = replanner_.plan();
    ASSERT_EQ(first_.decision, Decision::kFollowPlan) << first_.reason;
    ASSERT_GT(first_.plan.steps.size(), kDriven);
    domain::PlanReplay replay(ais_.map, replanner_.mission(), replanner_.progress());
    for (std::size_t k = 0; k < kDriven; ++k) {
      ASSERT_TRUE(replay.apply(first_.plan.steps[k]).has_value());
    }
    ASSERT_TRUE(replanner_.update(replay.progress(), replanner_.heading_end()).has_value());
    // From now on every search is stopped at once: only the safe answer is left.
    cancel_ = true;
  }

  std::vector<domain::PlanStep> rest() const {
    return {first_.plan.steps.begin() + kDriven, first_.plan.steps.end()};
  }
  PipeId pipe(std::string_view name) const { return pipe_named(ais_.map, name); }
  double middle(PipeId p) const { return ais_.map.pipe(p).length_m / 2; }

  // The answer is a valid plan from where the robot is.
  void expect_valid(const PlanResponse& r) const {
    domain::MissionProgress start = replanner_.progress();
    for (const auto& d : replanner_.dropped()) start.done[d.task.index()] = true;
    const auto report = domain::validate_plan(r.plan, ais_.map, replanner_.mission(), start);
    EXPECT_TRUE(report.valid) << report.error;
  }

  static constexpr std::size_t kDriven = 3;
  testing::AisTestbed ais_ = testing::load_ais_testbed();
  std::atomic<bool> cancel_{false};
  Replanner replanner_{
      ais_.map, ais_.mission, {.planner = {.cancel = &cancel_, .improvement_expansions = 0}}};
  PlanResponse first_;
};

// A replan for the battery (the executor's "battery low" when its estimate drifts) whose plan
// left still fits what the robot reports: it goes on, every task kept.
TEST_F(AnytimeReplan, ABatteryReplanOutOfTimeKeepsTheCurrentPlanThatStillFits) {
  const PlanResponse r = replanner_.plan("battery low");
  EXPECT_EQ(r.decision, Decision::kFollowPlan) << r.reason;
  EXPECT_EQ(r.plan.steps, rest());
  EXPECT_TRUE(r.newly_dropped.empty());
  EXPECT_NE(r.reason.find("the current plan still holds"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("cancelled"), std::string::npos) << r.reason;
  expect_valid(r);
}

// The same, but the battery left no longer covers the rest: the nearest exit instead.
TEST_F(AnytimeReplan, ABatteryReplanOutOfTimeHeadsForAnExitWhenTheRestNoLongerFits) {
  domain::MissionProgress low = replanner_.progress();
  const double budget_wh =
      ais_.mission.profile.battery_wh * (1 - ais_.mission.battery_reserve_fraction);
  // Enough to reach an exit (the first plan's energy, all of it, is far more), not for the rest.
  low.energy_used_wh = budget_wh - (first_.energy_wh - low.energy_used_wh) * 0.6;
  ASSERT_TRUE(replanner_.update(low, replanner_.heading_end()).has_value());
  const PlanResponse r = replanner_.plan("battery low");
  EXPECT_EQ(r.decision, Decision::kDegraded) << r.reason;
  EXPECT_NE(r.plan.steps, rest());
  EXPECT_EQ(r.end.rfind("exit ", 0), 0U) << r.end;
  expect_valid(r);
}

// A blockage met off the plan left (a detour the robot tried, a report from elsewhere): the rest
// of the current plan still holds.
TEST_F(AnytimeReplan, AFailureOffTheRouteOutOfTimeKeepsTheCurrentPlan) {
  const PipeId p10 = pipe("P10");
  const PlanResponse r = replanner_.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p10, .offset_m = middle(p10)});
  EXPECT_EQ(r.decision, Decision::kFollowPlan) << r.reason;
  EXPECT_EQ(r.plan.steps, rest());
  EXPECT_NE(r.reason.find("blockage in P10"), std::string::npos) << r.reason;
  expect_valid(r);
}

// A blockage on the plan left breaks it: the nearest exit, every task left dropped.
TEST_F(AnytimeReplan, AFailureOnTheRouteOutOfTimeHeadsForAnExit) {
  const PipeId p4 = pipe("P4");
  const PlanResponse r = replanner_.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = middle(p4)});
  EXPECT_EQ(r.decision, Decision::kDegraded) << r.reason;
  EXPECT_EQ(r.end.rfind("exit ", 0), 0U) << r.end;
  EXPECT_FALSE(r.newly_dropped.empty());
  expect_valid(r);
}

// What an earlier mission learnt, added now: off the route the current plan holds, on it not.
TEST_F(AnytimeReplan, ALearntFactOffTheRouteKeepsTheCurrentPlanAndOneOnItDoesNot) {
  ASSERT_TRUE(replanner_.learn({.blockages = {{pipe("P13"), middle(pipe("P13"))}}}).has_value());
  const PlanResponse off = replanner_.plan("learnt");
  EXPECT_EQ(off.decision, Decision::kFollowPlan) << off.reason;
  EXPECT_EQ(off.plan.steps, rest());
  ASSERT_TRUE(replanner_.learn({.blockages = {{pipe("P8"), middle(pipe("P8"))}}}).has_value());
  const PlanResponse on = replanner_.plan("learnt");
  EXPECT_EQ(on.decision, Decision::kDegraded) << on.reason;
  EXPECT_NE(on.plan.steps, rest());
  expect_valid(on);
}

// The robot somewhere the plan never went (it backed out part of a pipe): not the current plan.
TEST_F(AnytimeReplan, ARobotOffThePlanGetsTheNearestExit) {
  domain::MissionProgress moved = replanner_.progress();
  const PipeId p1 = pipe("P1");
  moved.position = domain::InPipe{p1, middle(p1)};
  ASSERT_TRUE(replanner_.update(moved, 0).has_value());
  const PlanResponse r = replanner_.plan("battery low");
  EXPECT_EQ(r.decision, Decision::kDegraded) << r.reason;
  EXPECT_EQ(r.end.rfind("exit ", 0), 0U) << r.end;
  expect_valid(r);
}

}  // namespace
}  // namespace sewerplan::executor
