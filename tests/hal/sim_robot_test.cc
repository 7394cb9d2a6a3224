// SPDX-License-Identifier: MIT
#include "sewerplan/hal/sim_robot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/hal/obstacle_clearing.h"

#include "support/ais_testbed.h"
#include "support/paths.h"
#include "support/small_map.h"

namespace sewerplan::hal {
namespace {

using ::testing::HasSubstr;

// M1 --P1 (20 m)-- M2 --P2 (10 m)-- M3 --P4 (5 m, blind)
//                  |
//                  P3 (10 m)
//                  |
//                  M4
// M2's slots: P1 (1), P2 (2), P3 (3).
class SimRobotTest : public ::testing::Test {
 protected:
  SimRobotTest()
      : map_(testing::SmallMap()
                 .manhole("M1", 0, 0, /*exit=*/true)
                 .manhole("M2", 20, 0)
                 .manhole("M3", 30, 0)
                 .manhole("M4", 20, 10)
                 .pipe("P1", "M1", "M2")
                 .pipe("P2", "M2", "M3")
                 .pipe("P3", "M2", "M4")
                 .pipe("P4", "M3", "", 0.5, 5.0)
                 .build()),
        profile_(*builtin_profile("makro-1.1")) {}

  PipeId pipe(std::string_view name) const { return *map_.find_pipe(name); }
  ManholeId manhole(std::string_view name) const { return *map_.find_manhole(name); }
  // In P1 at 5 m, heading for M2.
  InPipe in_p1() const { return InPipe{pipe("P1"), 5.0, Heading::kTowardsEnd1}; }
  SimRobot robot(SimPose start, FaultScenario faults = {}, SimOptions options = {}) const {
    return SimRobot(map_, profile_, start, std::move(faults), options);
  }
  FaultScenario obstacle_in_p1(ObstacleKind kind) const {
    FaultScenario f;
    f.obstacles.push_back({pipe("P1"), 12.3, kind});
    return f;
  }

  SewerMap map_;
  RobotProfile profile_;
};

constexpr DriveForward kDrive15{.speed_mps = 0.3, .distance_m = 15};

TEST_F(SimRobotTest, DrivesAlongAPipeIntoTheNextManholesMouth) {
  SimRobot r = robot(in_p1());
  JobReport report = r.execute(kDrive15);
  EXPECT_TRUE(report.ok()) << *report.error;
  EXPECT_DOUBLE_EQ(report.progress_m, 15);
  EXPECT_DOUBLE_EQ(report.duration_s, 50);
  EXPECT_DOUBLE_EQ(report.energy_wh, 50 * 120 / 3600.0);
  EXPECT_EQ(r.pose(), SimPose(AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole}));
  EXPECT_DOUBLE_EQ(r.status().odometry_m, 15);
  EXPECT_DOUBLE_EQ(r.status().elapsed_s, 50);
  EXPECT_DOUBLE_EQ(r.status().battery_wh, 240 - 50 * 120 / 3600.0);
}

TEST_F(SimRobotTest, AnEmergencyStopHoldsTheRobotWhereItIsUntilAReboot) {
  SimRobot r = robot(in_p1());
  r.emergency_stop();
  for (int i = 0; i < 2; ++i) {
    const JobReport stopped = r.execute(kDrive15);
    ASSERT_FALSE(stopped.ok());
    EXPECT_EQ(stopped.error->kind, RobotErrorKind::kMalfunction);
    EXPECT_EQ(stopped.error->reason, "emergency stop");
    EXPECT_DOUBLE_EQ(stopped.progress_m, 0);
    EXPECT_EQ(r.pose(), SimPose(in_p1()));
    EXPECT_DOUBLE_EQ(r.status().elapsed_s, 0);
  }
  ASSERT_TRUE(r.reboot().has_value());
  EXPECT_FALSE(r.emergency_stopped());
  EXPECT_TRUE(r.execute(kDrive15).ok());
}

TEST_F(SimRobotTest, ADriveBeyondAManholeStopsAtItsMouthWithoutError) {
  SimRobot r = robot(in_p1());
  JobReport report = r.execute(DriveForward{.speed_mps = 0.3, .distance_m = 100});
  EXPECT_TRUE(report.ok());
  EXPECT_DOUBLE_EQ(report.progress_m, 15);
  EXPECT_TRUE(std::holds_alternative<AtSlot>(r.pose()));
}

TEST_F(SimRobotTest, ADriveBeyondABlindEndIsABlockage) {
  SimRobot r = robot(InPipe{pipe("P4"), 1.0, Heading::kTowardsEnd1});
  JobReport report = r.execute(DriveForward{.speed_mps = 0.3, .distance_m = 10});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kBlockage);
  EXPECT_THAT(report.error->reason, HasSubstr("blind end of P4"));
  EXPECT_DOUBLE_EQ(report.progress_m, 4);
  // Exactly to the blind end is fine.
  SimRobot exact = robot(InPipe{pipe("P4"), 1.0, Heading::kTowardsEnd1});
  EXPECT_TRUE(exact.execute(DriveForward{.speed_mps = 0.3, .distance_m = 4}).ok());
}

// A drive to a manhole ends at a manhole it sees; a blind end where the map has a manhole (a
// lateral the world lacks) is a blockage even when the drive went as far as the map's length.
TEST_F(SimRobotTest, ADriveToAManholeThatMeetsABlindEndIsABlockage) {
  for (double distance : {3.0, 4.0}) {
    SimRobot r = robot(InPipe{pipe("P4"), 1.0, Heading::kTowardsEnd1});
    const JobReport report =
        r.execute(DriveForward{.speed_mps = 0.3, .distance_m = distance, .to_manhole = true});
    ASSERT_FALSE(report.ok()) << distance;
    EXPECT_EQ(report.error->kind, RobotErrorKind::kBlockage);
    EXPECT_THAT(report.error->reason, HasSubstr("blind end of P4"));
    EXPECT_FALSE(report.observation.has_value());
  }
}

TEST_F(SimRobotTest, StopsBeforeAPermanentObstacleWithBlockage) {
  SimRobot r = robot(in_p1(), obstacle_in_p1(ObstacleKind::kPermanent));
  JobReport report = r.execute(kDrive15);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kBlockage);
  EXPECT_EQ(report.error->reason, "obstacle in P1 at 12.30 m");
  EXPECT_DOUBLE_EQ(report.progress_m, 12.3 - 0.05 - 5.0);
  EXPECT_DOUBLE_EQ(std::get<InPipe>(r.pose()).offset_m, 12.25);
  EXPECT_DOUBLE_EQ(report.duration_s, (12.3 - 0.05 - 5.0) / 0.3);
  // Nothing clears it.
  EXPECT_TRUE(r.execute(LiftHead{}).ok());
  EXPECT_FALSE(r.execute(kDrive15).ok());
  JobReport push = r.execute(Push{.speed_mps = 0.1, .distance_m = 1});
  ASSERT_FALSE(push.ok());
  EXPECT_EQ(push.error->kind, RobotErrorKind::kBlockage);
  EXPECT_DOUBLE_EQ(push.progress_m, 0);
  EXPECT_EQ(r.remaining_obstacles().size(), 1U);
  // Backing away works.
  EXPECT_TRUE(r.execute(DriveBackward{.speed_mps = 0.3, .distance_m = 2}).ok());
  EXPECT_DOUBLE_EQ(std::get<InPipe>(r.pose()).offset_m, 10.25);
}

TEST_F(SimRobotTest, AnObstacleBlocksBothDirections) {
  SimRobot r = robot(InPipe{pipe("P1"), 15.0, Heading::kTowardsEnd1},
                     obstacle_in_p1(ObstacleKind::kPermanent));
  JobReport report = r.execute(DriveBackward{.speed_mps = 0.3, .distance_m = 10});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kBlockage);
  EXPECT_DOUBLE_EQ(report.progress_m, 15.0 - 12.3 - 0.05);
}

TEST_F(SimRobotTest, LiftingTheHeadNextToATransientLiftObstacleClearsIt) {
  SimRobot r = robot(in_p1(), obstacle_in_p1(ObstacleKind::kTransientLift));
  EXPECT_FALSE(r.execute(kDrive15).ok());
  JobReport lift = r.execute(LiftHead{});
  EXPECT_TRUE(lift.ok());
  EXPECT_DOUBLE_EQ(lift.duration_s, 3);
  EXPECT_TRUE(r.status().head_lifted);
  EXPECT_TRUE(r.remaining_obstacles().empty());
  EXPECT_TRUE(r.execute(LowerHead{}).ok());
  EXPECT_FALSE(r.status().head_lifted);
  JobReport report = r.execute(kDrive15);
  EXPECT_TRUE(report.ok());
  EXPECT_DOUBLE_EQ(report.progress_m, 20 - 12.25);
}

TEST_F(SimRobotTest, LiftingTheHeadFarFromATransientLiftObstacleDoesNothing) {
  SimRobot r = robot(in_p1(), obstacle_in_p1(ObstacleKind::kTransientLift));
  EXPECT_TRUE(r.execute(LiftHead{}).ok());
  EXPECT_EQ(r.remaining_obstacles().size(), 1U);
  EXPECT_FALSE(r.execute(kDrive15).ok());
}

TEST_F(SimRobotTest, APushClearsATransientPushObstacle) {
  SimRobot r = robot(in_p1(), obstacle_in_p1(ObstacleKind::kTransientPush));
  EXPECT_FALSE(r.execute(kDrive15).ok());
  EXPECT_TRUE(r.execute(LiftHead{}).ok());
  EXPECT_FALSE(r.execute(kDrive15).ok()) << "lifting does not clear a push obstacle";
  JobReport push = r.execute(Push{.speed_mps = 0.1, .distance_m = 1});
  EXPECT_TRUE(push.ok());
  EXPECT_DOUBLE_EQ(push.progress_m, 1);
  EXPECT_TRUE(r.remaining_obstacles().empty());
  EXPECT_TRUE(r.execute(kDrive15).ok());
  EXPECT_TRUE(std::holds_alternative<AtSlot>(r.pose()));
}

// Issue 30: an obstacle only a push clears, met while backing, is pushed backward with the rear
// head (the robot cannot turn in a pipe). Before, a push drove forward only and it stayed.
TEST_F(SimRobotTest, IssueThirtyABackwardPushClearsATransientPushObstacleBehindTheRobot) {
  // At 15 m facing end 1: the obstacle at 12.3 m is behind.
  SimRobot r = robot(InPipe{pipe("P1"), 15.0, Heading::kTowardsEnd1},
                     obstacle_in_p1(ObstacleKind::kTransientPush));
  const Job back = DriveBackward{.speed_mps = 0.3, .distance_m = 4};
  ASSERT_FALSE(r.execute(back).ok());
  EXPECT_DOUBLE_EQ(std::get<InPipe>(r.pose()).offset_m, 12.35);
  // A forward push drives away from it and leaves it there.
  EXPECT_TRUE(r.execute(Push{.speed_mps = 0.1, .distance_m = 0.5}).ok());
  EXPECT_EQ(r.remaining_obstacles().size(), 1U);
  EXPECT_DOUBLE_EQ(std::get<InPipe>(r.pose()).offset_m, 12.85);
  JobReport push = r.execute(Push{.speed_mps = 0.1, .distance_m = 1.5, .backward = true});
  EXPECT_TRUE(push.ok());
  EXPECT_DOUBLE_EQ(push.progress_m, 1.5);
  EXPECT_TRUE(r.remaining_obstacles().empty());
  EXPECT_DOUBLE_EQ(std::get<InPipe>(r.pose()).offset_m, 11.35);
  EXPECT_EQ(std::get<InPipe>(r.pose()).heading, Heading::kTowardsEnd1) << "it backed";
  // A backward push stops at a permanent obstacle behind, as a drive does.
  SimRobot p = robot(InPipe{pipe("P1"), 15.0, Heading::kTowardsEnd1},
                     obstacle_in_p1(ObstacleKind::kPermanent));
  JobReport blocked = p.execute(Push{.speed_mps = 0.1, .distance_m = 4, .backward = true});
  ASSERT_FALSE(blocked.ok());
  EXPECT_EQ(blocked.error->kind, RobotErrorKind::kBlockage);
  EXPECT_DOUBLE_EQ(blocked.progress_m, 15.0 - 12.35);
}

// The simulated robot clears obstacles as hal's one table says (obstacle_clearing.h), met front
// or rear first: lifting the head on either side, pushing on either side (backward when backing).
TEST_F(SimRobotTest, ClearsEachObstacleAsTheClearingTableSaysFromEitherSide) {
  for (const ObstacleKind kind :
       {ObstacleKind::kTransientLift, ObstacleKind::kTransientPush, ObstacleKind::kPermanent}) {
    for (const Approach approach : {Approach::kFront, Approach::kRear}) {
      const bool front = approach == Approach::kFront;
      // At 15 m facing end 1: the obstacle at 12.3 m is behind the robot.
      SimRobot r = robot(InPipe{pipe("P1"), front ? 10.0 : 15.0, Heading::kTowardsEnd1},
                         obstacle_in_p1(kind));
      const Job drive = front ? Job{DriveForward{.speed_mps = 0.3, .distance_m = 4}}
                              : Job{DriveBackward{.speed_mps = 0.3, .distance_m = 4}};
      ASSERT_FALSE(r.execute(drive).ok());
      // Every manoeuvre the robot has, where it stopped: the head, then a push the way it drove.
      EXPECT_TRUE(r.execute(LiftHead{}).ok());
      EXPECT_TRUE(r.execute(LowerHead{}).ok());
      static_cast<void>(r.execute(Push{.speed_mps = 0.1, .distance_m = 0.1, .backward = !front}));
      EXPECT_EQ(r.remaining_obstacles().empty(), clears_from(kind, approach))
          << to_string(kind) << (front ? " front" : " rear");
    }
  }
  static_assert(cleared_by(ObstacleKind::kTransientPush) == Clearing::kPush);
  static_assert(clears_from(ObstacleKind::kTransientPush, Approach::kRear));
  static_assert(clears_from(ObstacleKind::kTransientLift, Approach::kRear));
}

TEST_F(SimRobotTest, StopsBeforeADangerSpotWithDanger) {
  FaultScenario faults;
  faults.danger_spots.push_back({pipe("P1"), 10.0});
  SimRobot r = robot(in_p1(), faults);
  JobReport report = r.execute(kDrive15);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kDanger);
  EXPECT_EQ(report.error->reason, "danger in P1 at 10.00 m");
  EXPECT_DOUBLE_EQ(report.progress_m, 4.95);
}

TEST_F(SimRobotTest, ADangerousPassageFailsTheTurnInBothDirections) {
  FaultScenario faults;
  faults.dangerous_passages.push_back({manhole("M2"), SlotIndex{0}, SlotIndex{1}});
  const AtSlot at_p1{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole};
  SimRobot r = robot(at_p1, faults);
  JobReport report = r.execute(TurnInManhole{.from_slot = 0, .to_slot = 1, .duration_s = 20});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kDanger);
  EXPECT_EQ(report.error->reason, "dangerous passage in M2 from slot 1 to slot 2");
  EXPECT_EQ(r.pose(), SimPose(at_p1));

  SimRobot back = robot(AtSlot{manhole("M2"), SlotIndex{1}, Facing::kIntoManhole}, faults);
  EXPECT_FALSE(back.execute(TurnInManhole{.from_slot = 1, .to_slot = 0, .duration_s = 20}).ok());

  JobReport other = r.execute(TurnInManhole{.from_slot = 0, .to_slot = 2, .duration_s = 20});
  EXPECT_TRUE(other.ok());
  EXPECT_DOUBLE_EQ(other.duration_s, 20);
  EXPECT_EQ(r.pose(), SimPose(InPipe{pipe("P3"), 0.0, Heading::kTowardsEnd1}));
}

// A job started where the robot is not is typed apart from a job no robot could run: the controller
// relocalises on the first (its belief put the robot at a mouth it is not at) and never on the
// second (a CAN node's "too many waypoints" was once taken for the robot being lost).
TEST_F(SimRobotTest, TurningFromAnotherSlotIsAMalfunctionNotAtItsStart) {
  SimRobot r = robot(AtSlot{manhole("M2"), SlotIndex{1}, Facing::kIntoManhole});
  JobReport report = r.execute(TurnInManhole{.from_slot = 0, .to_slot = 2, .duration_s = 20});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_EQ(report.error->cause, RobotErrorCause::kNotAtStart);
  EXPECT_THAT(report.error->reason, HasSubstr("not at slot 1"));
  EXPECT_THAT(report.error->reason, HasSubstr("at M2 slot 2 (P2)"));
  SimRobot in_pipe = robot(in_p1());
  const JobReport turn_in_pipe = in_pipe.execute(TurnInManhole{.from_slot = 0, .to_slot = 1});
  ASSERT_FALSE(turn_in_pipe.ok());
  EXPECT_EQ(turn_in_pipe.error->cause, RobotErrorCause::kNotAtStart);
  const JobReport enter_in_pipe = in_pipe.execute(EnterPipeFromManhole{.slot = 0});
  ASSERT_FALSE(enter_in_pipe.ok());
  EXPECT_EQ(enter_in_pipe.error->cause, RobotErrorCause::kNotAtStart);
}

// A turn into a mouth the manhole does not have (the map has a lateral the sewer lacks) is a
// blockage of that passage, no-mouth, by slot number as by the mouths seen on arrival: the
// controller closes the way through it and plans again. Until 2026-12-07 it was invalid-job, a
// job no robot could run, and the controller held the robot and called the beacon `stuck`.
TEST_F(SimRobotTest, ATurnIntoAMouthTheManholeLacksIsANoMouthBlockage) {
  SimRobot r = robot(AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole});
  const JobReport by_slot =
      r.execute(TurnInManhole{.from_slot = 0, .to_slot = 3, .duration_s = 20});
  ASSERT_FALSE(by_slot.ok());
  EXPECT_EQ(by_slot.error->cause, RobotErrorCause::kNoMouth);
  EXPECT_EQ(by_slot.error->kind, RobotErrorKind::kBlockage);
  EXPECT_THAT(by_slot.error->reason, HasSubstr("M2 has no passage from slot 1 to slot 4"));
  EXPECT_DOUBLE_EQ(by_slot.progress_m, 0);
  EXPECT_EQ(r.pose(), SimPose(AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole}));
  const JobReport by_sighting =
      r.execute(TurnInManhole{.from_slot = kBySighting, .to_slot = 3, .duration_s = 20});
  ASSERT_FALSE(by_sighting.ok());
  EXPECT_EQ(by_sighting.error->cause, RobotErrorCause::kNoMouth);
  EXPECT_THAT(by_sighting.error->reason, HasSubstr("M2 has no mouth 4 seen from its arrival"));
  EXPECT_EQ(r.pose(), SimPose(AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole}));
  // The mouths it has are still there to turn into.
  EXPECT_TRUE(r.execute(TurnInManhole{.from_slot = 0, .to_slot = 2, .duration_s = 20}).ok());
}

// A turn whose numbers are wrong wherever it is sent stays a job no robot could run: a turn from a
// mouth into itself, a negative duration.
TEST_F(SimRobotTest, ATurnWithBadNumbersStaysAnInvalidJob) {
  const auto cause_of = [&](const TurnInManhole& job) {
    SimRobot r = robot(AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole});
    const JobReport report = r.execute(job);
    return report.ok() ? std::optional<RobotErrorCause>() : report.error->cause;
  };
  EXPECT_EQ(cause_of(TurnInManhole{.from_slot = 0, .to_slot = 0, .duration_s = 20}),
            RobotErrorCause::kInvalidJob);
  EXPECT_EQ(cause_of(TurnInManhole{.from_slot = 0, .to_slot = 1, .duration_s = -1}),
            RobotErrorCause::kInvalidJob);
  EXPECT_EQ(cause_of(TurnInManhole{.from_slot = kBySighting, .to_slot = 0, .duration_s = 20}),
            RobotErrorCause::kInvalidJob);
  EXPECT_EQ(cause_of(TurnInManhole{.from_slot = kBySighting, .to_slot = 1, .duration_s = -1}),
            RobotErrorCause::kInvalidJob);
}

TEST_F(SimRobotTest, TurnsIntoTheOtherPipeAtItsEndInTheManhole) {
  // P1 ends at M2 with its end 1: turning from P2 into P1 heads towards M1 (end 0).
  SimRobot r = robot(AtSlot{manhole("M2"), SlotIndex{1}, Facing::kIntoManhole});
  EXPECT_TRUE(r.execute(TurnInManhole{.from_slot = 1, .to_slot = 0, .duration_s = 20}).ok());
  EXPECT_EQ(r.pose(), SimPose(InPipe{pipe("P1"), 20.0, Heading::kTowardsEnd0}));
  JobReport report = r.execute(DriveForward{.speed_mps = 0.3, .distance_m = 20});
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(r.pose(), SimPose(AtSlot{manhole("M1"), SlotIndex{0}, Facing::kIntoManhole}));
}

TEST_F(SimRobotTest, ADriveOfZeroMetresAtAPipesEndReachesItsMouth) {
  // Just turned from P2 into P1: right at P1's M2 end, facing away from M2. Backing 0 m is
  // arriving at M2's mouth of P1 (a plan's "drive back to M2" after a go-to at that end).
  SimRobot r = robot(AtSlot{manhole("M2"), SlotIndex{1}, Facing::kIntoManhole});
  ASSERT_TRUE(r.execute(TurnInManhole{.from_slot = 1, .to_slot = 0, .duration_s = 20}).ok());
  const JobReport report = r.execute(DriveBackward{.speed_mps = 0.3, .distance_m = 0});
  EXPECT_TRUE(report.ok());
  EXPECT_DOUBLE_EQ(report.progress_m, 0);
  EXPECT_EQ(r.pose(), SimPose(AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoPipe}));
  // Elsewhere in a pipe, and at a mouth, 0 m is no move at all.
  SimRobot mid = robot(in_p1());
  EXPECT_TRUE(mid.execute(DriveForward{.speed_mps = 0.3, .distance_m = 0}).ok());
  EXPECT_EQ(mid.pose(), SimPose(in_p1()));
  const SimPose mouth = AtSlot{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole};
  SimRobot at = robot(mouth);
  EXPECT_TRUE(at.execute(DriveForward{.speed_mps = 0.3, .distance_m = 0}).ok());
  EXPECT_EQ(at.pose(), mouth);
}

TEST_F(SimRobotTest, EntersAPipeOnlyFromInsideAManhole) {
  SimRobot r = robot(InManhole{manhole("M1")});
  JobReport blocked = r.execute(kDrive15);
  ASSERT_FALSE(blocked.ok());
  EXPECT_EQ(blocked.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_TRUE(r.execute(EnterPipeFromManhole{.slot = 0, .duration_s = 20}).ok());
  EXPECT_EQ(r.pose(), SimPose(InPipe{pipe("P1"), 0.0, Heading::kTowardsEnd1}));
  EXPECT_FALSE(r.execute(EnterPipeFromManhole{.slot = 0}).ok());
}

// Out of the pipe the pipe's end stops a drive at once (as it stops one that reaches it); back
// into the pipe it drives.
TEST_F(SimRobotTest, AtAMouthOnlyTheWayBackIntoThePipeIsDrivable) {
  const AtSlot mouth{manhole("M2"), SlotIndex{0}, Facing::kIntoManhole};
  SimRobot r = robot(mouth);
  JobReport forward = r.execute(DriveForward{.speed_mps = 0.3, .distance_m = 1});
  EXPECT_TRUE(forward.ok());
  EXPECT_EQ(forward.progress_m, 0);
  EXPECT_EQ(r.pose(), SimPose(mouth));
  // A push does not pretend the manhole is not there: refused.
  EXPECT_FALSE(r.execute(Push{.speed_mps = 0.3, .distance_m = 1}).ok());
  EXPECT_TRUE(r.execute(DriveBackward{.speed_mps = 0.3, .distance_m = 20}).ok());
  // Backed out of P1 into M1's mouth, facing the pipe.
  EXPECT_EQ(r.pose(), SimPose(AtSlot{manhole("M1"), SlotIndex{0}, Facing::kIntoPipe}));
  EXPECT_TRUE(r.execute(DriveForward{.speed_mps = 0.3, .distance_m = 2}).ok());
  EXPECT_EQ(r.pose(), SimPose(InPipe{pipe("P1"), 2.0, Heading::kTowardsEnd1}));
}

TEST_F(SimRobotTest, ATransientMalfunctionLastsUntilAReboot) {
  FaultScenario faults;
  faults.malfunctions.push_back({AtJob{1}, MalfunctionKind::kTransient});
  SimRobot r = robot(in_p1(), faults);
  const DriveForward drive{.speed_mps = 0.3, .distance_m = 3};
  EXPECT_TRUE(r.execute(drive).ok());
  JobReport report = r.execute(drive);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_EQ(report.error->reason, "transient malfunction at job 1");
  EXPECT_DOUBLE_EQ(report.progress_m, 0);
  EXPECT_EQ(r.pose(), SimPose(InPipe{pipe("P1"), 8.0, Heading::kTowardsEnd1}));
  EXPECT_FALSE(r.execute(drive).ok());
  const double before_s = r.status().elapsed_s;
  EXPECT_TRUE(r.reboot().has_value());
  EXPECT_DOUBLE_EQ(r.status().elapsed_s, before_s + 30);
  EXPECT_TRUE(r.execute(drive).ok());
  EXPECT_DOUBLE_EQ(std::get<InPipe>(r.pose()).offset_m, 11);
}

TEST_F(SimRobotTest, APermanentMalfunctionStopsTheRobotForGood) {
  FaultScenario faults;
  faults.malfunctions.push_back({AtTime{20}, MalfunctionKind::kPermanent});
  SimRobot r = robot(in_p1(), faults);
  JobReport report = r.execute(kDrive15);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_EQ(report.error->reason, "permanent malfunction at 20.0 s");
  EXPECT_DOUBLE_EQ(report.duration_s, 20);
  EXPECT_DOUBLE_EQ(report.progress_m, 6);
  Result<void> reboot = r.reboot();
  ASSERT_FALSE(reboot.has_value());
  EXPECT_THAT(reboot.error().message, HasSubstr("permanent malfunction"));
  EXPECT_FALSE(r.execute(Stop{}).ok());
  EXPECT_FALSE(r.execute(LiftHead{}).ok());
}

TEST_F(SimRobotTest, AnEmptyBatteryStopsTheRobot) {
  FaultScenario faults;
  faults.battery_wh = 1.0;  // 30 s at 120 W
  SimRobot r = robot(in_p1(), faults);
  EXPECT_DOUBLE_EQ(r.status().battery_wh, 1.0);
  JobReport report = r.execute(kDrive15);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_EQ(report.error->reason, "battery empty");
  EXPECT_DOUBLE_EQ(report.progress_m, 9);
  EXPECT_DOUBLE_EQ(r.status().battery_wh, 0);
  JobReport next = r.execute(Stop{});
  ASSERT_FALSE(next.ok());
  EXPECT_EQ(next.error->reason, "battery empty");
  EXPECT_TRUE(r.reboot().has_value());
  EXPECT_FALSE(r.execute(LiftHead{}).ok());
}

TEST_F(SimRobotTest, ASampleTakesItsDurationAndAdvancesASharedClock) {
  ManualClock clock;
  SimRobot r = robot(in_p1(), {}, {.clock = &clock});
  JobReport report = r.execute(TakeSample{.duration_s = 180});
  EXPECT_TRUE(report.ok());
  EXPECT_DOUBLE_EQ(report.duration_s, 180);
  EXPECT_DOUBLE_EQ(clock.now_s(), 180);
  EXPECT_TRUE(r.execute(Stop{}).ok());
  EXPECT_DOUBLE_EQ(r.status().elapsed_s, 180);
  EXPECT_FALSE(r.status().beacon_on);
  r.activate_beacon();
  EXPECT_TRUE(r.status().beacon_on);
}

TEST_F(SimRobotTest, InvalidJobParametersAreMalfunctions) {
  SimRobot r = robot(in_p1());
  JobReport report = r.execute(DriveForward{.speed_mps = 0, .distance_m = 1});
  ASSERT_FALSE(report.ok());
  EXPECT_THAT(report.error->reason, HasSubstr("invalid job"));
  EXPECT_EQ(report.error->cause, RobotErrorCause::kInvalidJob);
  const JobReport sample = r.execute(TakeSample{.duration_s = -1});
  ASSERT_FALSE(sample.ok());
  EXPECT_EQ(sample.error->cause, RobotErrorCause::kInvalidJob);
}

TEST_F(SimRobotTest, TheSameScenarioAndJobsGiveTheSameReports) {
  FaultScenario faults = obstacle_in_p1(ObstacleKind::kTransientLift);
  faults.malfunctions.push_back({AtJob{2}, MalfunctionKind::kTransient});
  const std::vector<Job> jobs = {
      kDrive15, LiftHead{},  kDrive15,
      kDrive15, LowerHead{}, TurnInManhole{.from_slot = 0, .to_slot = 1, .duration_s = 25}};
  const auto run = [&] {
    SimRobot r = robot(in_p1(), faults);
    std::vector<JobReport> reports;
    for (const Job& job : jobs) {
      reports.push_back(r.execute(job));
      if (!reports.back().ok()) static_cast<void>(r.reboot());
    }
    return std::pair{reports, r.status()};
  };
  EXPECT_EQ(run(), run());
}

TEST(SimRobotAisTest, MeetsTheObstacleOfBlockedP5OnThePapersRoute) {
  const SewerMap map = testing::load_ais_testbed().map;
  Diagnostics d;
  Result<FaultScenario> faults =
      read_faults(testing::dataset_path("ais-testbed/faults/blocked-p5.json"), map, d);
  ASSERT_TRUE(faults.has_value()) << faults.error();
  // DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1 M3 P5 P2 P1, then DRIVE_PIPE_TO_MANHOLE P5 M6.
  SimRobot r(map, *builtin_profile("makro-1.1"),
             AtSlot{*map.find_manhole("M3"), SlotIndex{2}, Facing::kIntoManhole}, *faults);
  EXPECT_TRUE(r.execute(TurnInManhole{.from_slot = 2, .to_slot = 0, .duration_s = 26}).ok());
  JobReport report = r.execute(DriveForward{.speed_mps = 0.3, .distance_m = 10});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kBlockage);
  EXPECT_EQ(report.error->reason, "obstacle in P5 at 4.00 m");
  EXPECT_DOUBLE_EQ(report.progress_m, 3.95);
  EXPECT_EQ(describe(r.pose(), map), "in P5 at 3.95 m towards M6");
}

}  // namespace
}  // namespace sewerplan::hal
