// SPDX-License-Identifier: MIT
// The Replanner's answers: typed decisions the robot software switches on, on the paper's test
// environment (datasets/ais-testbed).
#include "sewerplan/executor/replanner.h"

#include <gtest/gtest.h>

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

TEST(ReplannerDecision, EveryDecisionHasAStableNameThatParsesBack) {
  const std::vector<std::pair<Decision, std::string_view>> names{
      {Decision::kFollowPlan, "follow-plan"},
      {Decision::kDegraded, "degraded"},
      {Decision::kCallForRecovery, "call-for-recovery"},
      {Decision::kStuck, "stuck"},
      {Decision::kInvalidReport, "invalid-report"}};
  for (const auto& [decision, name] : names) {
    EXPECT_EQ(to_string(decision), name);
    EXPECT_EQ(parse_decision(name), decision) << name;
  }
  EXPECT_EQ(parse_decision("follow"), std::nullopt);
  EXPECT_EQ(parse_decision("call for recovery"), std::nullopt);
}

TEST(ReplannerDecision, OnlyFollowAndDegradedCarryAPlanAndOnlyRecoveryAndStuckCallTheBeacon) {
  EXPECT_TRUE(has_plan(Decision::kFollowPlan));
  EXPECT_TRUE(has_plan(Decision::kDegraded));
  EXPECT_FALSE(has_plan(Decision::kCallForRecovery));
  EXPECT_FALSE(has_plan(Decision::kStuck));
  EXPECT_FALSE(has_plan(Decision::kInvalidReport));
  EXPECT_TRUE(calls_beacon(Decision::kCallForRecovery));
  EXPECT_TRUE(calls_beacon(Decision::kStuck));
  EXPECT_FALSE(calls_beacon(Decision::kFollowPlan));
  EXPECT_FALSE(calls_beacon(Decision::kDegraded));
  EXPECT_FALSE(calls_beacon(Decision::kInvalidReport));
}

TEST(ReplannerDecision, TheWholeMissionIsFollowPlan) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  const PlanResponse r = replanner.plan();
  EXPECT_EQ(r.decision, Decision::kFollowPlan) << r.reason;
  EXPECT_FALSE(r.plan.steps.empty());
}

TEST(ReplannerDecision, ABlockageThatCostsATaskIsDegraded) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  (void)replanner.plan();
  // Both ways into P4 blocked: the inspection cannot be done any more.
  const PipeId p4 = pipe_named(ais.map, "P4");
  (void)replanner.report_failure({.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = 0.5});
  const PlanResponse r = replanner.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = ais.map.pipe(p4).length_m - 0.5});
  EXPECT_EQ(r.decision, Decision::kDegraded) << r.reason;
  EXPECT_TRUE(has_plan(r.decision));
}

TEST(ReplannerDecision, ARobotThatCannotMoveIsStuck) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  const PlanResponse r =
      replanner.report_failure({.kind = Failure::Kind::kStuck, .detail = "motor 3 dead"});
  EXPECT_EQ(r.decision, Decision::kStuck);
  EXPECT_NE(r.reason.find("motor 3 dead"), std::string::npos);
}

}  // namespace
}  // namespace sewerplan::executor
