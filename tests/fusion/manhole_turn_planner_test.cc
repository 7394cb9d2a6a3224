// SPDX-License-Identifier: MIT
// The manhole turn planner against the paper's figures (sections 1, 2.1, 2.2): MAKRO turns up to
// 90 degrees and climbs steps of up to 30 cm, also both at once.
#include "sewerplan/fusion/manhole_turn_planner.h"

#include <atomic>
#include <cmath>

#include <gtest/gtest.h>

#include "sewerplan/core/robot_profile.h"
#include "sewerplan/fusion/manhole_geometry.h"

#include "ompl_planner.h"
#include "support/ticking_clock.h"

namespace sewerplan::fusion {
namespace {

class ManholeTurnPlannerTest : public ::testing::Test {
 protected:
  // Built with OMPL, with the motion library's planner, linked.
  void SetUp() override {
    if (!SEWERPLAN_TEST_WITH_OMPL) GTEST_SKIP() << "built without OMPL";
  }
  TurnPlan plan(const PassageGeometry& g, std::uint32_t seed = 1) const {
    ManholeTurnPlanner planner(testing::ompl_planner(), robot_body(profile_), profile_,
                               {.seed = seed});
    Result<TurnPlan> p = planner.plan(g);
    EXPECT_TRUE(p.has_value()) << p.error();
    return p.has_value() ? *p : TurnPlan{};
  }
  RobotProfile profile_ = *builtin_profile("makro-1.1");
};

PassageGeometry right_angle(double step_m = 0) {
  return PassageGeometry{.manhole_diameter_m = 1.0,
                         .turn_deg = 90,
                         .from_diameter_m = 0.6,
                         .to_diameter_m = 0.6,
                         .step_m = step_m};
}

TEST(RobotBodyTest, MakrosJointsFollowAFortyThreeCentimetreRadiusAndReachThirtyOneCentimetres) {
  const RobotBody body = robot_body(*builtin_profile("makro-1.1"));
  EXPECT_NEAR(body.segment_length_m, 2.0 / 6, 1e-12);
  EXPECT_NEAR(body.min_turn_radius_m(), 0.4355, 1e-3);
  EXPECT_NEAR(body.max_climb_m(), 0.3132, 1e-3);
  EXPECT_GT(body.bend_margin_m(), 0.0);
}

TEST(PassageGeometryTest, FreeSpaceIsTheManholeAndThePipeStrips) {
  const PassageGeometry g = right_angle();
  EXPECT_TRUE(in_free_space(g, 0, 0, 0.11));
  EXPECT_FALSE(in_free_space(g, 0.45, 0, 0.11));  // the wall opposite the from-pipe
  EXPECT_TRUE(in_free_space(g, -0.8, 0, 0.11));   // in the from-pipe
  EXPECT_TRUE(in_free_space(g, 0, 0.8, 0.11));    // in the to-pipe
  EXPECT_FALSE(in_free_space(g, 0, -0.8, 0.11));  // outside, behind the wall
  EXPECT_FALSE(in_free_space(g, -0.8, 0.25, 0.11));
}

TEST_F(ManholeTurnPlannerTest, StraightThroughIsFeasible) {
  PassageGeometry g = right_angle();
  g.turn_deg = 0;
  const TurnPlan p = plan(g);
  EXPECT_TRUE(p.feasible) << p.reason;
  // The head crosses the manhole (1 m) and drives the body's length (2 m) into the pipe.
  EXPECT_NEAR(p.path_length_m, 3.0, 0.05);
  EXPECT_NEAR(p.duration_s, 3.0 / profile_.manoeuvre_speed_mps, 1.0);
  ASSERT_FALSE(p.waypoints.empty());
  EXPECT_NEAR(p.waypoints.front().x_m, -0.5, 1e-3);
  EXPECT_NEAR(p.waypoints.back().x_m, 2.5, 1e-3);
}

TEST_F(ManholeTurnPlannerTest, ARightAngleInAOneMetreManholeBetweenSixtyCentimetrePipesIsFeasible) {
  const TurnPlan p = plan(right_angle());
  EXPECT_TRUE(p.feasible) << p.reason;
  EXPECT_GE(p.heading_change_deg, 90 - 1e-6);
  ASSERT_FALSE(p.waypoints.empty());
  // It ends in the to-pipe (azimuth 90: +y), the tail at the mouth.
  EXPECT_NEAR(p.waypoints.back().x_m, 0, 1e-3);
  EXPECT_NEAR(p.waypoints.back().y_m, 2.5, 1e-3);
  EXPECT_NEAR(p.waypoints.back().heading_deg, 90, 0.1);
  EXPECT_GT(p.duration_s, 0);
}

TEST_F(ManholeTurnPlannerTest, APipeNarrowerThanTheRobotIsNot) {
  PassageGeometry g = right_angle();
  g.to_diameter_m = 0.20;  // MAKRO is 0.22 m wide
  const TurnPlan p = plan(g);
  EXPECT_FALSE(p.feasible);
  EXPECT_NE(p.reason.find("narrower than the body"), std::string::npos) << p.reason;
}

TEST_F(ManholeTurnPlannerTest, AThirtyCentimetreStepWhileTurningIsFeasibleAsInThePaper) {
  const TurnPlan p = plan(right_angle(0.30));
  EXPECT_TRUE(p.feasible) << p.reason;
  ASSERT_FALSE(p.waypoints.empty());
  EXPECT_NEAR(p.waypoints.front().z_m, 0, 1e-9);
  EXPECT_NEAR(p.waypoints.back().z_m, 0.30, 1e-9);
  // Stepping down the same height is feasible too.
  EXPECT_TRUE(plan(right_angle(-0.30)).feasible);
}

TEST_F(ManholeTurnPlannerTest, AFortyCentimetreStepIsNot) {
  const TurnPlan p = plan(right_angle(0.40));
  EXPECT_FALSE(p.feasible);
  EXPECT_NE(p.reason.find("step of 0.40 m"), std::string::npos) << p.reason;
  PassageGeometry straight = right_angle(-0.40);
  straight.turn_deg = 0;
  EXPECT_FALSE(plan(straight).feasible);
}

TEST_F(ManholeTurnPlannerTest, TheSameSeedGivesTheSameResult) {
  const PassageGeometry g = right_angle(0.2);
  const TurnPlan a = plan(g, 7);
  const TurnPlan b = plan(g, 7);
  EXPECT_TRUE(a.feasible) << a.reason;
  EXPECT_EQ(a, b);
}

// Issue 14: the motion planner honours the stop condition of every algorithm.
TEST_F(ManholeTurnPlannerTest, ReturnsCancelledWhenTheFlagIsSet) {
  std::atomic<bool> cancel{true};
  const ManholeTurnPlanner planner(testing::ompl_planner(), robot_body(profile_), profile_);
  Result<TurnPlan> p = planner.plan(right_angle(), StopCondition().with_cancel(cancel));
  ASSERT_FALSE(p.has_value());
  EXPECT_EQ(p.error().code, ErrorCode::kCancelled);
}

// The deadline passes at the 5th clock read: the first is before OMPL starts, the others are
// OMPL's termination condition at its first RRT iterations, too few to reach the to-pipe. Without
// our condition inside OMPL's, the planner would answer the feasible plan.
TEST_F(ManholeTurnPlannerTest, StopsInsideOmplAtTheDeadlineOfTheInjectedClock) {
  const ManholeTurnPlanner planner(testing::ompl_planner(), robot_body(profile_), profile_);
  testing::TickingClock clock(1.0);
  Result<TurnPlan> p = planner.plan(right_angle(), StopCondition::at_deadline(clock, 5));
  ASSERT_FALSE(p.has_value());
  EXPECT_EQ(p.error().code, ErrorCode::kSearchLimit);
  EXPECT_EQ(clock.reads(), 5);
  // A deadline never reached leaves the plan as it is without one (deterministic).
  testing::TickingClock slow(1.0);
  Result<TurnPlan> q = planner.plan(right_angle(), StopCondition::at_deadline(slow, 1e12));
  ASSERT_TRUE(q.has_value()) << q.error();
  EXPECT_EQ(*q, plan(right_angle()));
  EXPECT_GT(slow.reads(), 5);
}

TEST_F(ManholeTurnPlannerTest, AUTurnInAOneMetreManholeIsNot) {
  PassageGeometry g = right_angle();
  g.turn_deg = 170;
  const TurnPlan p = plan(g);
  EXPECT_FALSE(p.feasible);
  EXPECT_FALSE(p.reason.empty());
}

TEST_F(ManholeTurnPlannerTest, NonPositiveSizesAreAnError) {
  PassageGeometry g = right_angle();
  g.manhole_diameter_m = 0;
  ManholeTurnPlanner planner(testing::ompl_planner(), robot_body(profile_), profile_);
  Result<TurnPlan> p = planner.plan(g);
  ASSERT_FALSE(p.has_value());
  EXPECT_EQ(p.error().code, ErrorCode::kInvalidArgument);
}

TEST_F(ManholeTurnPlannerTest, TheHeadSpacePassesOmplsSanityChecks) {
  ManholeTurnPlanner planner(testing::ompl_planner(), robot_body(profile_), profile_);
  Result<void> ok = planner.check_state_space(right_angle());
  EXPECT_TRUE(ok.has_value()) << ok.error();
}

// fusion plans no head path itself (head_path_planner.h): without a planner, a clear error, and
// the analytic checks and sanity checks alike.
TEST(ManholeTurnPlannerWithoutAHeadPathPlanner, SaysAMotionNeedsTheOmplMotionPlanner) {
  const RobotProfile profile = *builtin_profile("makro-1.1");
  const ManholeTurnPlanner planner(nullptr, robot_body(profile), profile);
  Result<TurnPlan> p = planner.plan(right_angle());
  ASSERT_FALSE(p.has_value());
  EXPECT_EQ(p.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_NE(p.error().message.find("a manhole motion needs the OMPL motion planner"),
            std::string::npos)
      << p.error().message;
  Result<void> space = planner.check_state_space(right_angle());
  ASSERT_FALSE(space.has_value());
  EXPECT_EQ(space.error(), p.error());
}

}  // namespace
}  // namespace sewerplan::fusion
