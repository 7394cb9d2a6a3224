// SPDX-License-Identifier: MIT
// The simulated robot's sensing (SimOptions::sensing, docs/simulation.md "Sensing"): odometry that
// slips, manholes missed or seen where there are none, noisy observations, and drives that end at
// a manhole (DriveForward::to_manhole).
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/hal/sim_robot.h"

#include "support/small_map.h"

namespace sewerplan::hal {
namespace {

using ::testing::HasSubstr;

// M1 --P1 (20 m)-- M2 --P2 (10 m)-- M3
//                  |
//                  P3 (10 m)
//                  |
//                  M4
// At M2, P2 goes straight on from P1; P3 turns off it.
class SensingTest : public ::testing::Test {
 protected:
  SensingTest()
      : map_(testing::SmallMap()
                 .manhole("M1", 0, 0, /*exit=*/true)
                 .manhole("M2", 20, 0)
                 .manhole("M3", 30, 0)
                 .manhole("M4", 20, 10)
                 .pipe("P1", "M1", "M2")
                 .pipe("P2", "M2", "M3")
                 .pipe("P3", "M4", "M2")
                 .build()),
        profile_(*builtin_profile("makro-1.1")) {}

  PipeId pipe(std::string_view name) const { return *map_.find_pipe(name); }
  ManholeId manhole(std::string_view name) const { return *map_.find_manhole(name); }
  SimRobot robot(SimPose start, SensingModel sensing) const {
    return SimRobot(map_, profile_, start, {}, SimOptions{.sensing = std::move(sensing)});
  }
  // The slot of M2 that `pipe` leaves by.
  SlotIndex m2_slot(std::string_view name) const {
    const auto slots = map_.slots(manhole("M2"));
    for (std::size_t i = 0; i < slots.size(); ++i) {
      if (slots[i].pipe == pipe(name)) return SlotIndex{static_cast<std::uint16_t>(i)};
    }
    return SlotIndex{0};
  }

  SewerMap map_;
  RobotProfile profile_;
};

TEST_F(SensingTest, OdometryErrorIsZeroMeanWithTheDriftAsItsStandardDeviation) {
  SimRobot r = robot(InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}, {.drift = 0.03, .seed = 3});
  constexpr int kDrives = 2000;  // at 10 m/s, within the battery
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kDrives; ++i) {
    const bool forward = i % 2 == 0;
    const JobReport report =
        forward ? r.execute(DriveForward{10, 10}) : r.execute(DriveBackward{10, 10});
    ASSERT_TRUE(report.ok());
    const double error = report.progress_m - 10;
    sum += error;
    sum2 += error * error;
  }
  // The truth stays in the simulator: back where it started after every pair.
  EXPECT_EQ(r.pose(), (SimPose{InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}}));
  const double mean = sum / kDrives;
  const double sd = std::sqrt(sum2 / kDrives - mean * mean);
  EXPECT_NEAR(sd, 0.3, 0.03);  // 3 % of 10 m
  EXPECT_NEAR(mean, 0, 4 * 0.3 / std::sqrt(kDrives));
}

TEST_F(SensingTest, OdometrySlipsTwiceAsMuchInAWetPipe) {
  std::vector<bool> wet(map_.pipe_count(), false);
  wet[pipe("P1").index()] = true;
  SimRobot r =
      robot(InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}, {.drift = 0.03, .wet = wet, .seed = 4});
  double sum2 = 0;
  // 10 m/s: 2,000 drives within the battery.
  for (int i = 0; i < 2000; ++i) {
    const JobReport report =
        i % 2 == 0 ? r.execute(DriveForward{10, 10}) : r.execute(DriveBackward{10, 10});
    sum2 += (report.progress_m - 10) * (report.progress_m - 10);
  }
  EXPECT_NEAR(std::sqrt(sum2 / 2000), 0.6, 0.06);
}

// The robot sees the water it drives through (JobReport::in_water), so it can tell its odometry
// is less certain there; in a dry pipe, and for a job that drives nothing, it reports none.
TEST_F(SensingTest, ADriveInAWetPipeReportsWater) {
  std::vector<bool> wet(map_.pipe_count(), false);
  wet[pipe("P1").index()] = true;
  SimRobot r =
      robot(InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}, {.drift = 0.03, .wet = wet, .seed = 4});
  EXPECT_TRUE(r.execute(DriveForward{0.3, 2}).in_water);
  EXPECT_TRUE(r.execute(DriveBackward{0.3, 2}).in_water);
  EXPECT_FALSE(r.execute(DriveForward{0.3, 0}).in_water);
  SimRobot dry = robot(InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}, {.drift = 0.03, .seed = 4});
  EXPECT_FALSE(dry.execute(DriveForward{0.3, 2}).in_water);
}

TEST_F(SensingTest, ObservesTheManholeADriveEndsAt) {
  SimRobot r = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1}, {.observe = true});
  const JobReport report = r.execute(DriveForward{0.3, 20, true});
  ASSERT_TRUE(report.ok());
  ASSERT_TRUE(report.observation.has_value());
  EXPECT_EQ(*report.observation, expected_signature(map_, manhole("M2"), m2_slot("P1")));
  EXPECT_EQ(report.observation->slots.size(), 3U);
  // A drive that ends in the pipe sees no manhole.
  SimRobot s = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1}, {.observe = true});
  EXPECT_FALSE(s.execute(DriveForward{0.3, 12}).observation.has_value());
}

// A drive out of the pipe from the mouth the robot stands at (the controller believed it short
// of the end, the pipe being shorter than mapped) ends there at once, as any drive that reaches
// the pipe's end does, and the robot sees the manhole. It was refused as an invalid job, and the
// controller rebooted a robot with nothing wrong with it until it called for recovery.
TEST_F(SensingTest, ADriveOutOfThePipeFromItsMouthEndsThereAtOnce) {
  for (const bool to_manhole : {false, true}) {
    SimRobot r = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1}, {.observe = true});
    ASSERT_TRUE(r.execute(DriveForward{0.3, 20, true}).ok());
    const JobReport again = r.execute(DriveForward{0.3, 1.5, to_manhole});
    EXPECT_TRUE(again.ok()) << again.error->reason;
    EXPECT_EQ(again.progress_m, 0);
    ASSERT_TRUE(again.observation.has_value());
    EXPECT_EQ(*again.observation, expected_signature(map_, manhole("M2"), m2_slot("P1")));
    EXPECT_EQ(r.pose(), (SimPose{AtSlot{manhole("M2"), m2_slot("P1"), Facing::kIntoManhole}}));
    // Backing away from the manhole drives into the pipe as before.
    EXPECT_NEAR(r.execute(DriveBackward{0.3, 5}).progress_m, 5, 1e-9);
  }
}

TEST_F(SensingTest, ANoisyObservationStillMatchesItsManhole) {
  SimRobot r = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1},
                     {.observe = true, .signature_noise = SignatureNoise{}, .seed = 5});
  const JobReport report = r.execute(DriveForward{0.3, 20, true});
  ASSERT_TRUE(report.observation.has_value());
  const ManholeSignature expected = expected_signature(map_, manhole("M2"), m2_slot("P1"));
  EXPECT_NE(*report.observation, expected);
  EXPECT_TRUE(check_signature(*report.observation).has_value());
  EXPECT_TRUE(compare(expected, *report.observation).matches)
      << compare(expected, *report.observation).reason;
}

// A turn through a manhole reports the angle the joints measured (JobReport::turn_measured_deg):
// the true direction of the mouth left by, counter-clockwise from the one come from, with the
// turn noise as its standard deviation; nothing from a robot that does not measure its turns, nor
// after a turn it could not make. Its draws leave the other sensing draws as they were.
TEST_F(SensingTest, ATurnReportsTheAngleTheJointsMeasured) {
  const SlotIndex from = m2_slot("P1");
  const SlotIndex to = m2_slot("P3");
  const double truly = std::fmod(
      map_.slot(manhole("M2"), to).azimuth_deg - map_.slot(manhole("M2"), from).azimuth_deg + 360.0,
      360.0);
  const TurnInManhole turn{.from_slot = from.value(), .to_slot = to.value(), .duration_s = 5};
  const TurnInManhole back{.from_slot = to.value(), .to_slot = from.value(), .duration_s = 5};
  SimRobot exact = robot(AtSlot{manhole("M2"), from, Facing::kIntoManhole}, {.observe = true});
  const JobReport unmeasured = exact.execute(turn);
  ASSERT_TRUE(unmeasured.ok());
  EXPECT_FALSE(unmeasured.turn_measured_deg.has_value());

  SimRobot r = robot(AtSlot{manhole("M2"), from, Facing::kIntoManhole},
                     {.observe = true, .turn_noise_deg = 1.0, .seed = 6});
  constexpr int kTurns = 400;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kTurns; ++i) {
    const JobReport there = r.execute(turn);
    ASSERT_TRUE(there.ok());
    ASSERT_TRUE(there.turn_measured_deg.has_value());
    EXPECT_GE(*there.turn_measured_deg, 0);
    EXPECT_LT(*there.turn_measured_deg, 360);
    const double error = *there.turn_measured_deg - truly;
    sum += error;
    sum2 += error * error;
    // Into P3 and back to its mouth, turn back into P1, and into P1 and back to M2 again.
    ASSERT_TRUE(r.execute(DriveForward{1, 0.5}).ok());
    ASSERT_TRUE(r.execute(DriveBackward{1, 0.5, true}).ok());
    ASSERT_TRUE(r.execute(back).ok());
    ASSERT_TRUE(r.execute(DriveForward{1, 0.5}).ok());
    ASSERT_TRUE(r.execute(DriveBackward{1, 0.5, true}).ok());
  }
  const double mean = sum / kTurns;
  EXPECT_NEAR(std::sqrt(sum2 / kTurns - mean * mean), 1.0, 0.1);
  EXPECT_NEAR(mean, 0, 4 * 1.0 / std::sqrt(kTurns));

  // A turn it cannot make reports no angle.
  const JobReport refused = r.execute(TurnInManhole{.from_slot = 9, .to_slot = 0});
  ASSERT_FALSE(refused.ok());
  EXPECT_FALSE(refused.turn_measured_deg.has_value());

  // Measuring turns changes no other draw: the same drives slip alike.
  SensingModel slipping{.drift = 0.03, .observe = true, .seed = 8};
  SimRobot a = robot(AtSlot{manhole("M2"), from, Facing::kIntoManhole}, slipping);
  slipping.turn_noise_deg = 1.0;
  SimRobot b = robot(AtSlot{manhole("M2"), from, Facing::kIntoManhole}, slipping);
  for (SimRobot* x : {&a, &b}) ASSERT_TRUE(x->execute(turn).ok());
  EXPECT_EQ(a.execute(DriveForward{0.3, 4}).progress_m, b.execute(DriveForward{0.3, 4}).progress_m);
}

TEST_F(SensingTest, AMissedManholeWithAWayStraightOnIsDrivenThrough) {
  SimRobot r =
      robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1}, {.missed_share = 1, .observe = true});
  const JobReport report = r.execute(DriveForward{0.3, 20, true});
  // 20 m of P1, then on through M2 into P2 until the bound: 0.25 x 20 + 2 = 7 m more.
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error->kind, RobotErrorKind::kBlockage);
  EXPECT_THAT(report.error->reason, HasSubstr("no manhole seen in P1"));
  EXPECT_FALSE(report.observation.has_value());
  EXPECT_NEAR(report.progress_m, 27, 1e-9);
  EXPECT_EQ(r.pose(), (SimPose{InPipe{pipe("P2"), 7, Heading::kTowardsEnd1}}));
}

TEST_F(SensingTest, AMissedManholeWithNoWayStraightOnStopsTheRobotUnobserved) {
  // From P3 (north) M2 has no way straight on: the pipe's end stops the robot.
  SimRobot r =
      robot(InPipe{pipe("P3"), 0, Heading::kTowardsEnd1}, {.missed_share = 1, .observe = true});
  const JobReport report = r.execute(DriveForward{0.3, 10, true});
  EXPECT_TRUE(report.ok());
  EXPECT_FALSE(report.observation.has_value());
  EXPECT_EQ(r.pose(), (SimPose{AtSlot{manhole("M2"), m2_slot("P3"), Facing::kIntoManhole}}));
}

// The way straight on through a missed manhole is a pipe the robot's body must fit: into a pipe
// narrower than its profile's smallest (a 0.10 m house connection the official ISYBAU sample has)
// it cannot drive on, and the pipe's end stops it, as where there is no way straight on.
TEST_F(SensingTest, AMissedManholeIsDrivenThroughOnlyIntoAPipeTheRobotFits) {
  const SewerMap narrow = testing::SmallMap()
                              .manhole("M1", 0, 0, /*exit=*/true)
                              .manhole("M2", 20, 0)
                              .manhole("M3", 30, 0)
                              .pipe("P1", "M1", "M2")
                              .pipe("P2", "M2", "M3", 0.10)
                              .build();
  SimRobot r(narrow, profile_, InPipe{*narrow.find_pipe("P1"), 0, Heading::kTowardsEnd1}, {},
             SimOptions{.sensing = {.missed_share = 1, .observe = true}});
  const JobReport report = r.execute(DriveForward{0.3, 20, true});
  EXPECT_TRUE(report.ok());
  EXPECT_FALSE(report.observation.has_value());
  EXPECT_NEAR(report.progress_m, 20, 1e-9);
  EXPECT_EQ(r.pose(),
            (SimPose{AtSlot{*narrow.find_manhole("M2"), SlotIndex{0}, Facing::kIntoManhole}}));
}

TEST_F(SensingTest, AFalseManholeStopsADriveToAManholeEarly) {
  SimRobot r = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1},
                     {.false_per_km = 500, .observe = true, .seed = 7});
  const JobReport report = r.execute(DriveForward{0.3, 20, true});
  ASSERT_TRUE(report.ok());
  ASSERT_TRUE(report.observation.has_value());
  EXPECT_EQ(report.observation->slots.size(), 2U);
  EXPECT_EQ(report.observation->slots[1].relative_deg, 180);
  const auto* in = std::get_if<InPipe>(&r.pose());
  ASSERT_NE(in, nullptr) << "stopped in the pipe, short of M2";
  EXPECT_LT(in->offset_m, 20);
  EXPECT_NEAR(report.progress_m, in->offset_m, 1e-9);
  // A drive of a distance (not to a manhole) never stops at a false one.
  SimRobot s = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1},
                     {.false_per_km = 500, .observe = true, .seed = 7});
  EXPECT_NEAR(s.execute(DriveForward{0.3, 15}).progress_m, 15, 1e-9);
}

TEST_F(SensingTest, ADriveToAManholeGoesOnPastTheMapsDistanceToTheManhole) {
  // The map said 12 m; the pipe is 20 m: the robot drives on (up to 12 + 5 m) until it is there.
  SimRobot r = robot(InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}, {});
  const JobReport report = r.execute(DriveForward{0.3, 12, true});
  EXPECT_TRUE(report.ok());
  EXPECT_NEAR(report.progress_m, 15, 1e-9);
  EXPECT_EQ(r.pose(), (SimPose{AtSlot{manhole("M2"), m2_slot("P1"), Facing::kIntoManhole}}));
  // Beyond the bound, it stops and says so.
  SimRobot s = robot(InPipe{pipe("P1"), 0, Heading::kTowardsEnd1}, {});
  const JobReport far = s.execute(DriveForward{0.3, 10, true});
  ASSERT_FALSE(far.ok());
  EXPECT_THAT(far.error->reason, HasSubstr("no manhole seen in P1 within 14.50 m"));
  // Without to_manhole, the distance is the distance.
  SimRobot t = robot(InPipe{pipe("P1"), 5, Heading::kTowardsEnd1}, {});
  EXPECT_NEAR(t.execute(DriveForward{0.3, 12}).progress_m, 12, 1e-9);
}

}  // namespace
}  // namespace sewerplan::hal
