// SPDX-License-Identifier: MIT
// Precomputing a map's passages, and fusion attaching the planned motions to PassManhole and its
// TurnInManhole job.
#include "sewerplan/fusion/passage_precompute.h"

#include <atomic>
#include <cmath>
#include <memory>
#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/fusion/fuse.h"
#include "sewerplan/fusion/jobs.h"

#include "ompl_planner.h"
#include "support/small_map.h"
#include "support/ticking_clock.h"

namespace sewerplan::fusion {
namespace {

using testing::SmallMap;

const HeadPathPlanner* ompl() { return testing::ompl_planner(); }

class PassagePrecomputeTest : public ::testing::Test {
 protected:
  // Built with OMPL, with the motion library's planner, linked.
  void SetUp() override {
    if (!SEWERPLAN_TEST_WITH_OMPL) GTEST_SKIP() << "built without OMPL";
  }
  // M2 has a straight way (P1 -> P3), a right angle (P1 -> P2) and, into P4, a 0.40 m step.
  SewerMap map_ = SmallMap()
                      .manhole("M1", 0, 0, true)
                      .manhole("M2", 10, 0)
                      .manhole("M3", 10, 10)
                      .manhole("M4", 20, 0)
                      .manhole("M5", 10, -10)
                      .pipe("P1", "M1", "M2", 0.6)
                      .pipe("P2", "M2", "M3", 0.6)
                      .pipe("P3", "M2", "M4", 0.6)
                      .pipe("P4", "M2", "M5", 0.6)
                      .invert("M2", "P4", 0.40)
                      .build();
  RobotProfile profile_ = *builtin_profile("makro-1.1");
  ManualClock clock_;
};

TEST_F(PassagePrecomputeTest, PlansEveryPassageOncePerGeometryAndComparesWithTheRules) {
  std::size_t progress_calls = 0;
  Result<PrecomputeResult> r = precompute_passage_motion(
      map_, profile_,
      {.head_paths = ompl(), .progress = [&](std::size_t, std::size_t) { ++progress_calls; }},
      clock_);
  ASSERT_TRUE(r.has_value()) << r.error();
  const PrecomputeStatistics& s = r->statistics;
  EXPECT_EQ(progress_calls, map_.manhole_count());
  EXPECT_EQ(s.passages, 12U);  // M2: 4 x 3 ordered slot pairs; the others have one slot
  EXPECT_EQ(r->table.size(), 12U);
  EXPECT_LT(s.distinct_geometries, s.passages);  // the two right angles P1 -> P2, P3 -> P4 ...
  // The rules reject the six passages with the 0.40 m step, and so does the planner.
  EXPECT_EQ(s.rules_allow, 6U);
  EXPECT_EQ(s.feasible, 6U);
  EXPECT_EQ(s.rejected_by_motion_rules_allow, 0U);
  EXPECT_EQ(s.allowed_by_motion_rules_reject, 0U);
  const ManholeId m2 = *map_.find_manhole("M2");
  const PassageMotion* into_step = r->table.find(m2, SlotIndex{0}, SlotIndex{3});
  ASSERT_NE(into_step, nullptr);
  EXPECT_FALSE(into_step->feasible);
  EXPECT_NE(into_step->reason.find("0.40 m"), std::string::npos);
}

// Issue 14: `motion precompute` honours the stop condition: a cancel before it starts, and a
// deadline that passes inside the first passage's OMPL planning (its 3rd clock read).
TEST_F(PassagePrecomputeTest, StopsOnTheCancelFlagAndAtTheDeadline) {
  std::atomic<bool> cancel{true};
  Result<PrecomputeResult> cancelled = precompute_passage_motion(
      map_, profile_, {.head_paths = ompl(), .stop = StopCondition().with_cancel(cancel)}, clock_);
  ASSERT_FALSE(cancelled.has_value());
  EXPECT_EQ(cancelled.error().code, ErrorCode::kCancelled);
  testing::TickingClock ticking(1.0);
  Result<PrecomputeResult> late = precompute_passage_motion(
      map_, profile_, {.head_paths = ompl(), .stop = StopCondition::at_deadline(ticking, 3)},
      clock_);
  ASSERT_FALSE(late.has_value());
  EXPECT_EQ(late.error().code, ErrorCode::kSearchLimit);
  EXPECT_EQ(ticking.reads(), 3);
}

// Issue 14: after the last passage, the map's fingerprint and the release of the plans ask the
// stop too, and the table is made only after the last check: a deadline at the run's last clock
// read ends it without a table, one read later lets it finish.
TEST_F(PassagePrecomputeTest, AsksTheStopWhileAssemblingAndReleasing) {
  testing::TickingClock counting(1.0);
  ASSERT_TRUE(precompute_passage_motion(
                  map_, profile_,
                  {.head_paths = ompl(), .stop = StopCondition::at_deadline(counting, 1e12)},
                  clock_)
                  .has_value());
  const double reads = counting.reads();
  testing::TickingClock at_last(1.0);
  Result<PrecomputeResult> late = precompute_passage_motion(
      map_, profile_, {.head_paths = ompl(), .stop = StopCondition::at_deadline(at_last, reads)},
      clock_);
  ASSERT_FALSE(late.has_value());
  EXPECT_EQ(late.error().code, ErrorCode::kSearchLimit);
  testing::TickingClock after_last(1.0);
  Result<PrecomputeResult> done = precompute_passage_motion(
      map_, profile_,
      {.head_paths = ompl(), .stop = StopCondition::at_deadline(after_last, reads + 1)}, clock_);
  ASSERT_TRUE(done.has_value()) << done.error();
  EXPECT_EQ(done->table.size(), 12U);
}

// fusion plans no head path itself (head_path_planner.h): without a planner, no table.
TEST(PassagePrecomputeWithoutAHeadPathPlanner, IsAnErrorSayingItNeedsTheOmplMotionPlanner) {
  const SewerMap map = SmallMap().manhole("M1", 0, 0, true).build();
  ManualClock clock;
  Result<PrecomputeResult> r =
      precompute_passage_motion(map, *builtin_profile("makro-1.1"), {}, clock);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_NE(r.error().message.find("needs the OMPL motion planner"), std::string::npos)
      << r.error().message;
}

TEST_F(PassagePrecomputeTest, TheCacheReleasesItsPlansInSlices) {
  PassageMotionCache cache(ManholeTurnPlanner(ompl(), robot_body(profile_), profile_));
  for (double turn : {0.0, 45.0, 90.0}) {
    ASSERT_TRUE(cache.plan(PassageGeometry{.turn_deg = turn}).has_value());
  }
  EXPECT_EQ(cache.size(), 3U);
  EXPECT_TRUE(cache.release(2));
  EXPECT_EQ(cache.size(), 1U);
  EXPECT_FALSE(cache.release(2));
  EXPECT_EQ(cache.size(), 0U);
  EXPECT_FALSE(cache.release(1));
}

TEST_F(PassagePrecomputeTest, WaypointsAreInTheManholesFrame) {
  Result<PrecomputeResult> r =
      precompute_passage_motion(map_, profile_, {.head_paths = ompl()}, clock_);
  ASSERT_TRUE(r.has_value()) << r.error();
  const ManholeId m2 = *map_.find_manhole("M2");
  // P1 arrives from the west (its slot's azimuth is 180), P2 leaves north (90): a left turn.
  const PassageMotion* left = r->table.find(m2, SlotIndex{0}, SlotIndex{1});
  ASSERT_NE(left, nullptr);
  ASSERT_TRUE(left->feasible) << left->reason;
  ASSERT_GE(left->waypoints.size(), 2U);
  EXPECT_NEAR(left->waypoints.front().x_m, -0.5, 0.05);
  EXPECT_NEAR(left->waypoints.back().y_m, 2.5, 0.01);
  EXPECT_NEAR(left->waypoints.back().heading_deg, 90, 0.1);
  // P3 arrives from the east into P4 south: a right turn, mirrored.
  const PassageMotion* right = r->table.find(m2, SlotIndex{2}, SlotIndex{1});
  ASSERT_NE(right, nullptr);
  ASSERT_TRUE(right->feasible) << right->reason;
  EXPECT_NEAR(right->waypoints.front().x_m, 0.5, 0.05);
  EXPECT_NEAR(right->waypoints.back().y_m, 2.5, 0.01);  // P2 is north: from east, a right turn
  EXPECT_NEAR(right->waypoints.back().heading_deg, 90, 0.1);
}

TEST_F(PassagePrecomputeTest, TheSameSeedGivesTheSameTable) {
  Result<PrecomputeResult> a =
      precompute_passage_motion(map_, profile_, {.head_paths = ompl()}, clock_);
  Result<PrecomputeResult> b =
      precompute_passage_motion(map_, profile_, {.head_paths = ompl()}, clock_);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->table, b->table);
}

TEST_F(PassagePrecomputeTest, FusionAttachesTheWaypointsToThePassageAndItsJob) {
  Result<PrecomputeResult> r =
      precompute_passage_motion(map_, profile_, {.head_paths = ompl()}, clock_);
  ASSERT_TRUE(r.has_value()) << r.error();
  Mission mission = testing::small_mission(map_, "M1");
  mission.passage_motion = std::make_shared<const PassageMotionTable>(r->table);
  const ManholeId m1 = *map_.find_manhole("M1");
  const ManholeId m2 = *map_.find_manhole("M2");
  const domain::Plan plan{{domain::EnterPipe{m1, *map_.find_pipe("P1")},
                           domain::DrivePipeToManhole{*map_.find_pipe("P1"), m2},
                           domain::DriveManhole{m2, SlotIndex{0}, SlotIndex{1}}}};
  Result<FusedPlan> fused = fuse(plan, map_, mission, domain::initial_progress(mission, map_));
  ASSERT_TRUE(fused.has_value()) << fused.error();
  const auto& pass = std::get<PassManhole>(fused->actions[2]);
  const PassageMotion* motion = r->table.find(m2, SlotIndex{0}, SlotIndex{1});
  EXPECT_EQ(pass.waypoints, motion->waypoints);
  EXPECT_EQ(pass.duration_s, motion->duration_s);
  const std::vector<Job> jobs = expand(fused->actions[2], profile_);
  ASSERT_EQ(jobs.size(), 1U);
  EXPECT_EQ(std::get<TurnInManhole>(jobs[0]).waypoints, motion->waypoints);
  std::ostringstream text;
  text << jobs[0];
  EXPECT_NE(text.str().find(std::to_string(motion->waypoints.size()) + " waypoints"),
            std::string::npos)
      << text.str();

  // Without the table: the rules' duration and no waypoints.
  mission.passage_motion.reset();
  fused = fuse(plan, map_, mission, domain::initial_progress(mission, map_));
  ASSERT_TRUE(fused.has_value()) << fused.error();
  EXPECT_TRUE(std::get<PassManhole>(fused->actions[2]).waypoints.empty());
}

}  // namespace
}  // namespace sewerplan::fusion
