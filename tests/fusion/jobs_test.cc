// SPDX-License-Identifier: MIT
// Each robot action's base-machine jobs, and the jobs of the paper's plan fused.
#include "sewerplan/fusion/jobs.h"

#include <sstream>

#include <gtest/gtest.h>

#include "fusion/fusion_testing.h"
#include "support/ais_testbed.h"

namespace sewerplan::fusion {
namespace {

const RobotProfile& profile() {
  static const RobotProfile p = *builtin_profile("makro-1.1");
  return p;
}

// ... that ends where the robot sees the manhole (to_manhole): the map's distance may be wrong.
TEST(ExpandTest, ADriveToAManholeIsOneDriveInItsDirection) {
  DriveToManhole forward{.direction = Direction::kForward, .distance_m = 2.5, .speed_mps = 0.3};
  EXPECT_EQ(
      expand(forward, profile()),
      std::vector<Job>{(DriveForward{.speed_mps = 0.3, .distance_m = 2.5, .to_manhole = true})});
  DriveToManhole backward = forward;
  backward.direction = Direction::kBackward;
  EXPECT_EQ(
      expand(backward, profile()),
      std::vector<Job>{(DriveBackward{.speed_mps = 0.3, .distance_m = 2.5, .to_manhole = true})});
}

// A drive to a manhole of 0 m still takes a robot right at the pipe's end onto the mouth (the
// executor used to add that job itself); a 0 m approach to a point is no job.
TEST(ExpandTest, ADriveOfZeroMetresToAManholeIsAJobAndToAPointNone) {
  EXPECT_EQ(
      expand(DriveToManhole{.distance_m = 0, .speed_mps = 0.3}, profile()),
      std::vector<Job>{(DriveForward{.speed_mps = 0.3, .distance_m = 0, .to_manhole = true})});
  EXPECT_EQ(
      expand(DriveToManhole{.direction = Direction::kBackward, .distance_m = 0, .speed_mps = 0.3},
             profile()),
      std::vector<Job>{(DriveBackward{.speed_mps = 0.3, .distance_m = 0, .to_manhole = true})});
  EXPECT_TRUE(expand(GoToPoint{.drive = {Direction::kForward, 0, 0.3}}, profile()).empty());
}

TEST(ExpandTest, APassageIsOneTurnWithTheActionsParameters) {
  const PassManhole pass{.manhole = ManholeId{5},
                         .from_slot = SlotIndex{2},
                         .to_slot = SlotIndex{3},
                         .turn_deg = 90,
                         .step_m = -0.1,
                         .manhole_diameter_m = 1.5,
                         .duration_s = 57};
  EXPECT_EQ(expand(pass, profile()), std::vector<Job>{(TurnInManhole{.from_slot = 2,
                                                                     .to_slot = 3,
                                                                     .turn_deg = 90,
                                                                     .step_m = -0.1,
                                                                     .manhole_diameter_m = 1.5,
                                                                     .duration_s = 57})});
}

TEST(ExpandTest, EnteringAPipeIsOneEnterJob) {
  EXPECT_EQ(expand(EnterPipe{.slot = SlotIndex{1}, .duration_s = 20}, profile()),
            std::vector<Job>{(EnterPipeFromManhole{.slot = 1, .duration_s = 20})});
}

TEST(ExpandTest, ASampleDrivesToTheSpotStopsAndSamples) {
  const TakeWaterSample sample{
      .offset_m = 3, .drive = {Direction::kForward, 3, 0.3}, .sample_s = 180, .duration_s = 190};
  EXPECT_EQ(expand(sample, profile()),
            (std::vector<Job>{DriveForward{.speed_mps = 0.3, .distance_m = 3}, Stop{},
                              TakeSample{.duration_s = 180}}));
  const TakeWaterSample here{.drive = {Direction::kForward, 0, 0.3}, .sample_s = 180};
  EXPECT_EQ(expand(here, profile()), (std::vector<Job>{Stop{}, TakeSample{.duration_s = 180}}));
}

TEST(ExpandTest, AnInspectionApproachesThenScansTheWholePipe) {
  const InspectPipe inspect{
      .length_m = 8, .speed_mps = 0.1, .approach = {Direction::kBackward, 2, 0.3}};
  EXPECT_EQ(expand(inspect, profile()),
            (std::vector<Job>{DriveBackward{.speed_mps = 0.3, .distance_m = 2},
                              Scan{.speed_mps = 0.1, .distance_m = 8}}));
}

TEST(ExpandTest, AnInspectionThatFinishesWhereTheRobotCameInScansBackward) {
  const InspectPipe inspect{.length_m = 8,
                            .speed_mps = 0.1,
                            .scan_direction = Direction::kBackward,
                            .approach = {Direction::kForward, 2, 0.3}};
  EXPECT_EQ(expand(inspect, profile()),
            (std::vector<Job>{DriveForward{.speed_mps = 0.3, .distance_m = 2},
                              Scan{.speed_mps = 0.1, .distance_m = 8, .backward = true}}));
}

TEST(ExpandTest, GoingToAPointDrivesAndGoingToAManholeDoesNothing) {
  EXPECT_EQ(expand(GoToPoint{.drive = {Direction::kBackward, 1.5, 0.3}}, profile()),
            std::vector<Job>{(DriveBackward{.speed_mps = 0.3, .distance_m = 1.5})});
  EXPECT_TRUE(expand(GoToManhole{}, profile()).empty());
}

TEST(ExpandPlanTest, ThePapersPlanGivesItsJobsWithActionAndJobIndices) {
  const sewerplan::testing::AisTestbed ais = sewerplan::testing::load_ais_testbed();
  Result<FusedPlan> fused =
      testing::fuse_text(sewerplan::testing::kCorrectedPaperPlan, ais.map, ais.mission);
  ASSERT_TRUE(fused.has_value()) << fused.error();

  const std::vector<PlannedJob> jobs = expand_plan(*fused, ais.mission.profile);
  std::ostringstream kinds;
  for (const PlannedJob& j : jobs)
    kinds << j.action_index << '.' << j.job_index << job_kind(j.job) << ' ';
  // The drive of 0 m to M5 after the inspection (action 10) takes the robot from the pipe's end,
  // where the scan leaves it, onto the mouth.
  EXPECT_EQ(kinds.str(),
            "0.0drive_forward 1.0turn_in_manhole 2.0drive_forward 3.0turn_in_manhole "
            "4.0drive_forward 5.0turn_in_manhole 6.0drive_forward 6.1stop 6.2take_sample "
            "7.0drive_backward 8.0turn_in_manhole 9.0scan 10.0drive_forward 11.0turn_in_manhole "
            "12.0drive_forward 13.0turn_in_manhole ");
  std::ostringstream first;
  first << jobs.at(7);
  EXPECT_EQ(first.str(), "action 6 job 1: Stop");
}

}  // namespace
}  // namespace sewerplan::fusion
