// SPDX-License-Identifier: MIT
// What staged recovery clears agrees with what the campaign's oracle assumes it clears
// (executor::recovery_clears, hal/obstacle_clearing.h): every kind of obstacle, met driving
// forward and backward, with and without pushing. And a second obstacle behind one a push cleared
// gets recovery of its own and is reported with its own words and place (issue 30).
#include "sewerplan/hal/obstacle_clearing.h"

#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/executor/recovery_clears.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "dead_reckoning.h"
#include "staged_recovery.h"
#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

// The robot in P5 (10 m, from M3 to M6) at 5 m, its front towards M6; one job with staged
// recovery, on the simulated robot.
struct Bench {
  explicit Bench(std::vector<hal::Obstacle> obstacles, RecoveryProfile recovery)
      : ais(testing::load_ais_testbed()),
        pipe(*ais.map.find_pipe("P5")),
        config(recovery),
        robot(ais.map, ais.mission.profile, hal::InPipe{pipe, 5.0, hal::Heading::kTowardsEnd1},
              hal::FaultScenario{.obstacles = std::move(obstacles)}),
        tracker(ais.map, domain::InPipe{pipe, 5.0}, 1),
        recovery_(ais.map, config, 0.1, tracker,
                  {.execute_job =
                       [this](const Job& job) {
                         hal::JobReport r = robot.execute(job);
                         tracker.advance(job, r);
                         jobs.push_back(job);
                         return r;
                       },
                   .reboot = [this] { return robot.reboot(); },
                   .log_recovery = [](RecoveryPhase, bool) {}}) {}

  std::optional<Failure> run(const Job& job) { return recovery_.run_job(job, action); }

  double offset() const { return std::get<hal::InPipe>(robot.pose()).offset_m; }

  testing::AisTestbed ais;
  PipeId pipe;
  RecoveryProfile config;
  hal::SimRobot robot;
  detail::DeadReckoning tracker;
  fusion::RobotAction action = fusion::DriveToManhole{};
  std::vector<Job> jobs;
  detail::StagedRecovery recovery_;
};

hal::Obstacle obstacle(const testing::AisTestbed& ais, double offset_m, hal::ObstacleKind kind) {
  return hal::Obstacle{*ais.map.find_pipe("P5"), offset_m, kind};
}

// Issue 30: with --allow-push the oracle took every push-only obstacle for cleared, but the robot
// pushed with its front head only: one met while backing stayed, and 19 of 2,000 AIS runs at harsh
// rates missed an exit the oracle counted on. Recovery clears exactly what recovery_clears says,
// for each side, and the oracle asks recovery_clears.
TEST(ObstacleClearing, WhatRecoveryClearsIsWhatTheOracleAssumesInBothDirections) {
  const auto ais = testing::load_ais_testbed();
  for (const hal::ObstacleKind kind :
       {hal::ObstacleKind::kTransientLift, hal::ObstacleKind::kTransientPush,
        hal::ObstacleKind::kPermanent}) {
    for (const bool push_allowed : {false, true}) {
      for (const bool backward : {false, true}) {
        RecoveryProfile config;
        config.push_allowed = push_allowed;
        // 1.5 m ahead of the robot, the way it drives.
        Bench bench({obstacle(ais, backward ? 3.5 : 6.5, kind)}, config);
        const Job drive = backward ? Job{DriveBackward{0.1, 3.0}} : Job{DriveForward{0.1, 3.0}};
        const std::optional<Failure> failure = bench.run(drive);
        const bool cleared = !failure.has_value();
        const std::string what = std::string(hal::to_string(kind)) +
                                 (push_allowed ? ", push allowed" : "") +
                                 (backward ? ", backward" : ", forward");
        EXPECT_EQ(cleared, recovery_clears(config, kind,
                                           backward ? hal::Approach::kRear : hal::Approach::kFront))
            << what;
        if (cleared) {
          EXPECT_NEAR(bench.offset(), backward ? 2.0 : 8.0, 1e-9) << what;
        } else {
          ASSERT_EQ(failure->kind, Failure::Kind::kBlockage) << what;
          EXPECT_NEAR(failure->offset_m, backward ? 3.549 : 6.451, 1e-9) << what;
        }
      }
    }
  }
}

TEST(ObstacleClearing, WhatRecoveryClearsFollowsTheTableAndTheStagesItTries) {
  using hal::Approach;
  using hal::ObstacleKind;
  RecoveryProfile no_push;
  RecoveryProfile push;
  push.push_allowed = true;
  for (const Approach a : {Approach::kFront, Approach::kRear}) {
    EXPECT_TRUE(recovery_clears(no_push, ObstacleKind::kTransientLift, a));
    EXPECT_FALSE(recovery_clears(no_push, ObstacleKind::kTransientPush, a));
    EXPECT_FALSE(recovery_clears(push, ObstacleKind::kPermanent, a));
  }
  EXPECT_TRUE(recovery_clears(push, ObstacleKind::kTransientPush, Approach::kFront));
  EXPECT_TRUE(recovery_clears(push, ObstacleKind::kTransientPush, Approach::kRear));
  // A stage with no tries clears nothing.
  for (RecoveryStage& stage : push.stages) stage.tries = 0;
  EXPECT_FALSE(recovery_clears(push, ObstacleKind::kTransientLift, Approach::kFront));
  EXPECT_FALSE(recovery_clears(push, ObstacleKind::kTransientPush, Approach::kFront));
  // Nor does one the profile leaves out.
  push.stages = {{RecoveryPhase::kLiftHeadAndRetry, 1}};
  EXPECT_TRUE(recovery_clears(push, ObstacleKind::kTransientLift, Approach::kFront));
  EXPECT_FALSE(recovery_clears(push, ObstacleKind::kTransientPush, Approach::kFront));
}

// Issue 30: a push-only obstacle met while backing (and while scanning backward) is pushed
// backward, with the rear head, the rest of the drive; the robot ends where the drive would have.
// Before, staged recovery tried no push for a backward drive and the obstacle stayed.
TEST(ObstacleClearing, IssueThirtyAPushOnlyObstacleMetWhileBackingIsPushedBackward) {
  const auto ais = testing::load_ais_testbed();
  RecoveryProfile config;
  config.push_allowed = true;
  for (const Job& drive : {Job{DriveBackward{0.1, 3.0}}, Job{Scan{0.1, 3.0, true}}}) {
    Bench bench({obstacle(ais, 3.5, hal::ObstacleKind::kTransientPush)}, config);
    EXPECT_EQ(bench.run(drive), std::nullopt) << drive;
    EXPECT_NEAR(bench.offset(), 2.0, 1e-9) << drive;
    EXPECT_TRUE(bench.robot.remaining_obstacles().empty()) << drive;
    std::vector<Push> pushes;
    for (const Job& job : bench.jobs) {
      if (const auto* p = std::get_if<Push>(&job)) pushes.push_back(*p);
    }
    ASSERT_EQ(pushes.size(), 1U) << drive;
    EXPECT_TRUE(pushes[0].backward) << drive;
    // The controller's dead reckoning follows the push backward.
    const auto* in = std::get_if<domain::InPipe>(&bench.tracker.position());
    ASSERT_NE(in, nullptr);
    EXPECT_NEAR(in->offset_m, 2.0, 1e-9) << drive;
  }
}

// Issue 30: a push cleared the first obstacle and was stopped by a second one further on; that
// one got no recovery of its own and was reported with the first one's words (4 of 2,000 runs).
TEST(ObstacleClearing, ASecondObstacleBehindAPushedOneGetsItsOwnRecoveryAndItsOwnWords) {
  const auto ais = testing::load_ais_testbed();
  RecoveryProfile config;
  config.push_allowed = true;
  const Job drive = DriveForward{0.1, 4.0};  // from 5 m: a push at 6 m, the second at 7.5 m
  {
    // The second one the head lifts away: cleared by its own recovery, the drive done.
    Bench bench({obstacle(ais, 6.0, hal::ObstacleKind::kTransientPush),
                 obstacle(ais, 7.5, hal::ObstacleKind::kTransientLift)},
                config);
    EXPECT_EQ(bench.run(drive), std::nullopt);
    EXPECT_NEAR(bench.offset(), 9.0, 1e-9);
    EXPECT_TRUE(bench.robot.remaining_obstacles().empty());
  }
  {
    // A permanent one: reported there, in its own words.
    Bench bench({obstacle(ais, 6.0, hal::ObstacleKind::kTransientPush),
                 obstacle(ais, 7.5, hal::ObstacleKind::kPermanent)},
                config);
    const std::optional<Failure> failure = bench.run(drive);
    ASSERT_TRUE(failure.has_value());
    EXPECT_EQ(failure->kind, Failure::Kind::kBlockage);
    EXPECT_NEAR(failure->offset_m, 7.451, 1e-9);
    EXPECT_EQ(failure->detail, "obstacle in P5 at 7.50 m");
    // It got recovery of its own: backing up after the first push, and a push of its own.
    std::size_t pushes = 0;
    std::size_t drives_after_push = 0;
    for (const Job& job : bench.jobs) {
      if (std::holds_alternative<Push>(job)) {
        ++pushes;
      } else if (pushes > 0) {
        ++drives_after_push;
      }
    }
    EXPECT_EQ(pushes, 2U);
    EXPECT_GT(drives_after_push, 0U);
  }
}

}  // namespace
}  // namespace sewerplan::executor
