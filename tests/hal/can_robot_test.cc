// SPDX-License-Identifier: MIT
// CanRobot against the simulated node: the same reports as the simulated robot in process, and
// every bus fault ends as docs/can-protocol.md says - repaired by a retry, or a MALFUNCTION with a
// clear reason that a reboot over the bus clears.
#include "sewerplan/hal/can/can_robot.h"

#include <future>
#include <limits>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/robot_profile.h"

#include "support/can_node.h"
#include "support/small_map.h"

namespace sewerplan::hal {
namespace {

using testing::CanNodeThread;
using ::testing::HasSubstr;
using testing::Transport;

// Short timeouts: the node answers at once, and faults should not make the tests slow.
CanRobotOptions fast() {
  return {.ack_timeout_s = 0.15, .link_timeout_s = 0.3, .heartbeat_s = 0.05};
}

// M1 -P1- M2 -P2- M3, P1 20 m long.
class CanRobotTest : public ::testing::TestWithParam<Transport> {
 protected:
  CanRobotTest()
      : map_(testing::SmallMap()
                 .manhole("M1", 0, 0, /*exit=*/true)
                 .manhole("M2", 20, 0)
                 .manhole("M3", 30, 0)
                 .pipe("P1", "M1", "M2")
                 .pipe("P2", "M2", "M3")
                 .build()),
        profile_(*builtin_profile("makro-1.1")) {}

  SimPose start() const { return InPipe{*map_.find_pipe("P1"), 5.0, Heading::kTowardsEnd1}; }
  std::unique_ptr<CanNodeThread> node(BusFaults bus_faults = {}, FaultScenario faults = {},
                                      double heartbeat_s = 0.5) {
    return std::make_unique<CanNodeThread>(map_, profile_, start(), std::move(faults),
                                           std::move(bus_faults), GetParam(), heartbeat_s);
  }
  static BusFaults faults(std::string_view spec) {
    Result<BusFaults> f = parse_bus_faults(spec);
    EXPECT_TRUE(f.has_value()) << f.error().message;
    return f.has_value() ? *f : BusFaults{};
  }

  const std::vector<Job> jobs_{
      DriveForward{0.3, 4},
      LiftHead{},
      TakeSample{20},
      LowerHead{},
      DriveForward{0.3, 30},  // to M2's mouth, 11 m
      TurnInManhole{0, 1, 180, 0, 1, 12, {{0, 0, 0, 0}, {0.1, 0.1, 0, 90}}},
      Scan{0.2, 5, false},
  };
  SewerMap map_;
  RobotProfile profile_;
};

TEST_P(CanRobotTest, JobsOverTheBusGiveTheSimulatedRobotsReportsBitForBit) {
  SimRobot local(map_, profile_, start());
  auto n = node();
  ASSERT_TRUE(n->ok());
  // Long timeouts: a clean bus never waits for one, and a loaded machine cannot force a retry.
  CanRobot robot(n->controller_bus(), {.ack_timeout_s = 5, .link_timeout_s = 10});
  ASSERT_TRUE(robot.connect().has_value());
  EXPECT_EQ(robot.status(), local.status());
  for (const Job& job : jobs_) {
    EXPECT_EQ(robot.execute(job), local.execute(job)) << job;
    EXPECT_EQ(robot.status(), local.status()) << job;
  }
  robot.activate_beacon();
  EXPECT_TRUE(robot.status().beacon_on);
  EXPECT_EQ(robot.stats().retries, 0U);
  n->stop();
  EXPECT_EQ(n->robot().pose(), local.pose());
}

TEST_P(CanRobotTest, ARobotFailureCrossesTheBusWithItsReason) {
  FaultScenario f;
  f.obstacles.push_back({*map_.find_pipe("P1"), 12.0, ObstacleKind::kPermanent});
  f.malfunctions.push_back({AtJob{1}, MalfunctionKind::kPermanent});
  auto n = node({}, f);
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  const JobReport blocked = robot.execute(DriveForward{0.3, 10});
  ASSERT_FALSE(blocked.ok());
  EXPECT_EQ(blocked.error->kind, RobotErrorKind::kBlockage);
  EXPECT_EQ(blocked.error->reason, "obstacle in P1 at 12.00 m");
  EXPECT_DOUBLE_EQ(blocked.progress_m, 6.95);
  const JobReport broken = robot.execute(LiftHead{});
  EXPECT_EQ(broken.error->kind, RobotErrorKind::kMalfunction);
  const Result<void> reboot = robot.reboot();
  ASSERT_FALSE(reboot.has_value());
  EXPECT_EQ(reboot.error().message, "reboot failed: permanent malfunction at job 1");
}

// The node types its errors with the wire codes: a turn into a mouth M2 does not have is
// no-mouth (0x14) on the controller's side too, the words and numbers as the robot's own.
TEST_P(CanRobotTest, ATurnIntoAMouthTheManholeLacksCrossesTheBusAsNoMouth) {
  SimRobot local(map_, profile_, start());
  auto n = node();
  CanRobot robot(n->controller_bus(), {.ack_timeout_s = 5, .link_timeout_s = 10});
  ASSERT_TRUE(robot.connect().has_value());
  const std::vector<Job> jobs{DriveForward{0.3, 30}, TurnInManhole{0, 2, 90, 0, 1, 12, {}}};
  JobReport last;
  for (const Job& job : jobs) {
    last = robot.execute(job);
    EXPECT_EQ(last, local.execute(job)) << job;
  }
  ASSERT_FALSE(last.ok());
  EXPECT_EQ(last.error->cause, RobotErrorCause::kNoMouth);
  EXPECT_EQ(last.error->kind, RobotErrorKind::kBlockage);
  EXPECT_THAT(last.error->reason, HasSubstr("M2 has no passage from slot 1 to slot 3"));
  n->stop();
}

TEST_P(CanRobotTest, NoNodeMeansConnectTimesOut) {
  auto [a, b] = make_memory_can_pair();
  CanRobot robot(*a, fast());
  const Result<void> up = robot.connect();
  ASSERT_FALSE(up.has_value());
  EXPECT_EQ(up.error().code, ErrorCode::kCanTimeout);
  EXPECT_THAT(up.error().message, HasSubstr("no node answered"));
}

// Node frames: connect's status is frames 0-4; job 0's ack is 5, progress 6, result 7-14.
TEST_P(CanRobotTest, ALostAcknowledgementOrResultIsRepairedByARetry) {
  for (const char* spec : {"drop=5", "drop=9", "drop=14", "drop=5,6,7,8,9,10,11,12,13,14"}) {
    SimRobot local(map_, profile_, start());
    auto n = node(faults(spec));
    CanRobot robot(n->controller_bus(), fast());
    ASSERT_TRUE(robot.connect().has_value());
    EXPECT_EQ(robot.execute(jobs_[0]), local.execute(jobs_[0])) << spec;
    EXPECT_EQ(robot.execute(jobs_[1]), local.execute(jobs_[1])) << spec;
    // A lost acknowledgement needs no retry when the result comes.
    EXPECT_GE(robot.stats().retries, std::string_view(spec) == "drop=5" ? 0U : 1U) << spec;
    n->stop();
    EXPECT_EQ(n->node().stats().jobs_run, 2U) << spec << ": a job ran twice";
  }
}

TEST_P(CanRobotTest, GarbageOnTheLineIsDroppedAndTheJobGoesThrough) {
  SimRobot local(map_, profile_, start());
  auto n = node(faults("garbage=5,9"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  EXPECT_EQ(robot.execute(jobs_[0]), local.execute(jobs_[0]));
  EXPECT_GE(robot.stats().bad_input, 1U);
}

TEST_P(CanRobotTest, ALateAcknowledgementIsWaitedForOrRetried) {
  SimRobot local(map_, profile_, start());
  auto n = node(faults("late-ack=0@0.4"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  EXPECT_EQ(robot.execute(jobs_[0]), local.execute(jobs_[0]));
  EXPECT_EQ(robot.execute(jobs_[1]), local.execute(jobs_[1]));
  EXPECT_GE(robot.stats().retries, 1U);
  n->stop();
  EXPECT_EQ(n->node().stats().jobs_run, 2U);
}

// An acknowledgement later than every send and every result request (0.3 s + 3 x 0.2 s here;
// 1.5 s + 3 x 2 s with the defaults): the node, busy, goes on sending heartbeats, so the controller
// waits for the result. The simulated node used to sleep through the delay, silent, and the
// mission ended in a lost link and a failed reboot.
TEST_P(CanRobotTest, AnAcknowledgementLaterThanEveryRetryChangesNothingWhileTheNodeIsAlive) {
  SimRobot local(map_, profile_, start());
  auto n = node(faults("late-ack=0@1.5"), {}, /*heartbeat_s=*/0.05);
  CanRobot robot(n->controller_bus(),
                 {.ack_timeout_s = 0.1, .link_timeout_s = 0.2, .heartbeat_s = 0.05});
  ASSERT_TRUE(robot.connect().has_value());
  EXPECT_EQ(robot.execute(jobs_[0]), local.execute(jobs_[0]));
  EXPECT_EQ(robot.execute(jobs_[1]), local.execute(jobs_[1]));
  EXPECT_EQ(robot.stats().link_failures, 0U);
  EXPECT_EQ(robot.stats().emergency_stops, 0U);
  n->stop();
  EXPECT_EQ(n->node().stats().jobs_run, 2U);
  EXPECT_EQ(n->robot().pose(), local.pose());
}

TEST_P(CanRobotTest, SilenceIsAMalfunctionThatARebootOverTheBusClears) {
  // Request 0 is connect's; the job is sent 3 times (1-3) into the silence.
  auto n = node(faults("silence=1+3"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  const JobReport r = robot.execute(jobs_[0]);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_THAT(r.error->reason, HasSubstr("CAN link: no acknowledgement of job 2"));
  EXPECT_THAT(r.error->reason, HasSubstr("3 attempts"));
  EXPECT_EQ(robot.stats().emergency_stops, 1U);
  ASSERT_TRUE(robot.reboot().has_value());
  EXPECT_TRUE(robot.execute(jobs_[0]).ok());
}

// The link loses a job's PROGRESS and RESULT, every copy, until the reboot (lose-result): the
// node did the job, the controller does not know how far. The reboot asks the node before
// anything else is sent, and recovered_report() is the node's own report of the job: the turn
// done, the drive to its end. Sent again from where the controller last heard of the robot, the
// turn was refused ("not at slot 1 of a manhole"), as a malfunction, until the robot was stuck.
TEST_P(CanRobotTest, AJobWhoseResultTheLinkLostIsReportedByTheNodeAfterTheReboot) {
  for (const std::size_t lost : {std::size_t{4}, std::size_t{5}}) {  // the drive, the turn
    SimRobot local(map_, profile_, start());
    auto n = node(faults("lose-result=" + std::to_string(lost)));
    CanRobot robot(n->controller_bus(), fast());
    ASSERT_TRUE(robot.connect().has_value());
    for (std::size_t i = 0; i < jobs_.size(); ++i) {
      const JobReport own = local.execute(jobs_[i]);
      if (i != lost) {
        EXPECT_EQ(robot.execute(jobs_[i]), own) << jobs_[i];
        continue;
      }
      const JobReport heard = robot.execute(jobs_[i]);
      ASSERT_FALSE(heard.ok());
      EXPECT_THAT(heard.error->reason, HasSubstr("CAN link: no result of job"));
      EXPECT_EQ(heard.progress_m, 0);  // the PROGRESS was lost too
      EXPECT_FALSE(robot.recovered_report());
      ASSERT_TRUE(robot.reboot().has_value());
      ASSERT_TRUE(local.reboot().has_value());
      EXPECT_EQ(robot.recovered_report(), std::optional(own)) << jobs_[i];
      EXPECT_FALSE(robot.recovered_report());  // taken once
      EXPECT_EQ(robot.status(), local.status());
    }
    n->stop();
    EXPECT_EQ(n->node().stats().jobs_run, jobs_.size()) << "a job ran twice";
  }
}

// A job that never reached the node (its frames lost into a silence): after the reboot the node
// says it does not know it (ACK kUnknown), and the report says so, with no progress.
TEST_P(CanRobotTest, AJobThatNeverReachedTheNodeIsReportedSoAfterTheReboot) {
  auto n = node(faults("silence=1+3"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  const JobReport heard = robot.execute(jobs_[0]);
  ASSERT_FALSE(heard.ok());
  EXPECT_THAT(heard.error->reason, HasSubstr("the node does not know job 2"));
  ASSERT_TRUE(robot.reboot().has_value());
  const std::optional<JobReport> own = robot.recovered_report();
  ASSERT_TRUE(own);
  ASSERT_FALSE(own->ok());
  EXPECT_THAT(own->error->reason, HasSubstr("job 2 never reached the node"));
  EXPECT_EQ(own->progress_m, 0);
}

// The beacon is reported as the node answered: on (its STATUS says so), requested but unconfirmed
// (a silent node), or not sent at all (a bus that refuses every frame). It was "on" in every case.
TEST_P(CanRobotTest, TheBeaconIsConfirmedOnlyByTheNodesAnswer) {
  {
    auto n = node();
    CanRobot robot(n->controller_bus(), fast());
    ASSERT_TRUE(robot.connect().has_value());
    EXPECT_EQ(robot.activate_beacon(), BeaconState::kConfirmed);
    EXPECT_TRUE(robot.status().beacon_on);
  }
  {
    auto n = node(faults("silence=1+100"));
    CanRobot robot(n->controller_bus(), fast());
    ASSERT_TRUE(robot.connect().has_value());
    EXPECT_EQ(robot.activate_beacon(), BeaconState::kUnconfirmed);
    EXPECT_FALSE(robot.status().beacon_on);
  }
  {
    auto n = node(faults("bus-off=1"));  // at the job: the adapter refuses all that follows
    CanRobot robot(n->controller_bus(), fast());
    ASSERT_TRUE(robot.connect().has_value());
    EXPECT_FALSE(robot.execute(jobs_[0]).ok());
    EXPECT_EQ(robot.activate_beacon(), BeaconState::kNotSent);
  }
}

TEST_P(CanRobotTest, BusOffIsAMalfunctionThatARebootOverTheBusClears) {
  auto n = node(faults("bus-off=1"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  const JobReport r = robot.execute(jobs_[0]);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_THAT(r.error->reason, HasSubstr("CAN link: "));
  EXPECT_THAT(r.error->reason, ::testing::AnyOf(HasSubstr("bus-off"), HasSubstr("BEL"),
                                                HasSubstr("no acknowledgement")));
  ASSERT_TRUE(robot.reboot().has_value());
  const JobReport again = robot.execute(jobs_[0]);
  EXPECT_TRUE(again.ok()) << *again.error;
}

TEST_P(CanRobotTest, ADeadNodeEndsInAFailedReboot) {
  auto n = node(faults("silence=1+1000"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  EXPECT_FALSE(robot.execute(jobs_[0]).ok());
  const Result<void> reboot = robot.reboot();
  ASSERT_FALSE(reboot.has_value());
  EXPECT_EQ(reboot.error().code, ErrorCode::kCanTimeout);
  EXPECT_THAT(reboot.error().message, HasSubstr("reboot failed: no answer over CAN"));
}

TEST_P(CanRobotTest, AnEmergencyStopLatchesUntilAReboot) {
  auto n = node(faults("silence=1+3"));
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  EXPECT_FALSE(robot.execute(jobs_[0]).ok());  // and the emergency stop reaches the node
  const JobReport refused = robot.execute(jobs_[0]);
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.error->reason, HasSubstr("refused"));
  ASSERT_TRUE(robot.reboot().has_value());
  EXPECT_TRUE(robot.execute(jobs_[0]).ok());
}

TEST_P(CanRobotTest, AnEmergencyStopAskedForIsSentAndHoldsTheRobotUntilAReboot) {
  auto n = node();
  CanRobot robot(n->controller_bus(), fast());
  ASSERT_TRUE(robot.connect().has_value());
  robot.emergency_stop();  // as Executor::halt() does, from any thread
  const JobReport stopped = robot.execute(jobs_[0]);
  ASSERT_FALSE(stopped.ok());
  EXPECT_EQ(stopped.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_EQ(stopped.error->reason, "emergency stop");
  EXPECT_EQ(robot.stats().emergency_stops, 1U);
  EXPECT_EQ(robot.stats().link_failures, 0U);
  ASSERT_TRUE(robot.reboot().has_value());
  EXPECT_TRUE(robot.execute(jobs_[0]).ok());
  n->stop();
  EXPECT_EQ(n->node().stats().emergency_stops, 1U);  // it reached the node
  EXPECT_EQ(n->node().stats().jobs_run, 1U);         // the job asked for while stopped was not sent
}

// The steady clock, which also tells another thread once the controller has timed out `timeouts`
// times in the job it waits on: the clock is read on the controller's thread, so it may look at
// the robot's stats there.
class WaitingSignal final : public Clock {
 public:
  explicit WaitingSignal(std::size_t timeouts) : timeouts_(timeouts) {}
  void watch(const CanRobot& robot) { robot_ = &robot; }
  std::future<void> waiting() { return waiting_.get_future(); }
  double now_s() const override {
    if (robot_ != nullptr && !signalled_ && robot_->stats().timeouts >= timeouts_) {
      signalled_ = true;
      waiting_.set_value();
    }
    return steady_.now_s();
  }

 private:
  std::size_t timeouts_;
  const CanRobot* robot_ = nullptr;
  SteadyClock steady_;
  mutable bool signalled_ = false;
  mutable std::promise<void> waiting_;
};

// Executor::halt() while the controller waits on a job that the node holds back (late-ack 30 s):
// while it waits for the acknowledgement (1 timeout), and while it waits for the result after
// every send has timed out (3). The stop ends the wait, reaches the node, and the held job never
// runs (the simulated node used to sleep through the delay and run the job after the stop).
TEST_P(CanRobotTest, AnEmergencyStopWhileTheControllerWaitsOnAJobEndsItAndTheJobNeverRuns) {
  for (const std::size_t timeouts : {1U, 3U}) {
    SimRobot local(map_, profile_, start());
    auto n = node(faults("late-ack=0@30"), {}, /*heartbeat_s=*/0.05);
    WaitingSignal clock(timeouts);
    CanRobotOptions options{.ack_timeout_s = 0.1, .link_timeout_s = 0.2, .heartbeat_s = 0.05};
    options.clock = &clock;
    CanRobot robot(n->controller_bus(), options);
    ASSERT_TRUE(robot.connect().has_value());
    clock.watch(robot);
    std::future<void> waiting = clock.waiting();
    std::thread halt([&] {
      waiting.wait();
      robot.emergency_stop();  // as Executor::halt() does
    });
    const JobReport stopped = robot.execute(jobs_[0]);
    halt.join();
    ASSERT_FALSE(stopped.ok()) << timeouts;
    EXPECT_EQ(stopped.error->reason, "emergency stop") << timeouts;
    EXPECT_EQ(stopped.progress_m, 0) << timeouts;
    EXPECT_EQ(robot.stats().link_failures, 0U) << timeouts;
    EXPECT_GE(robot.stats().timeouts, timeouts);
    // After a reboot the next job runs, the held one does not.
    ASSERT_TRUE(robot.reboot().has_value()) << timeouts;
    EXPECT_EQ(robot.execute(jobs_[1]), local.execute(jobs_[1])) << timeouts;
    n->stop();
    EXPECT_EQ(n->node().stats().emergency_stops, 1U) << timeouts;
    EXPECT_EQ(n->node().stats().jobs_run, 1U) << timeouts;
    EXPECT_EQ(n->robot().pose(), local.pose()) << timeouts;
  }
}

// Executor::halt() during a reboot that the node does not answer (silent from the reboot on): the
// stop ends the wait after the first attempt's timeout instead of after every attempt's (6 s with
// the default timeouts), the reboot fails as stopped, reaches the node, and the stop holds: the
// next job is not sent.
TEST_P(CanRobotTest, AnEmergencyStopDuringARebootEndsItsWait) {
  auto n = node(faults("silence=1+100"), {}, /*heartbeat_s=*/0.05);
  WaitingSignal clock(0);  // signals once the reboot waits for its answer
  // Long timeouts: without the stop the reboot would wait 3 x 5 s.
  CanRobotOptions options{.ack_timeout_s = 5, .link_timeout_s = 5, .heartbeat_s = 0.05};
  options.clock = &clock;
  CanRobot robot(n->controller_bus(), options);
  ASSERT_TRUE(robot.connect().has_value());  // request 0, answered
  clock.watch(robot);
  std::future<void> waiting = clock.waiting();
  std::thread halt([&] {
    waiting.wait();
    robot.emergency_stop();  // as Executor::halt() does
  });
  const Result<void> rebooted = robot.reboot();
  halt.join();
  ASSERT_FALSE(rebooted.has_value());
  EXPECT_EQ(rebooted.error().code, ErrorCode::kCancelled);
  EXPECT_THAT(rebooted.error().message, HasSubstr("emergency stop"));
  EXPECT_EQ(robot.stats().timeouts, 0U);  // not options.attempts (3)
  EXPECT_EQ(robot.stats().retries, 0U);
  const JobReport held = robot.execute(jobs_[0]);
  ASSERT_FALSE(held.ok());
  EXPECT_EQ(held.error->reason, "emergency stop");
  n->stop();
  EXPECT_EQ(n->node().stats().jobs_run, 0U);
}

TEST_P(CanRobotTest, AFloodOfGarbageIsAMalfunctionThatSaysSo) {
  auto n = node(faults("garbage=5,6,7,8"));
  CanRobotOptions options = fast();
  options.max_bad_input = 2;
  CanRobot robot(n->controller_bus(), options);
  ASSERT_TRUE(robot.connect().has_value());
  const JobReport r = robot.execute(jobs_[0]);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_THAT(r.error->reason, HasSubstr("3 bad inputs, the last: "));
  EXPECT_THAT(r.error->reason, ::testing::AnyOf(HasSubstr("garbled line"), HasSubstr("garbage")));
}

INSTANTIATE_TEST_SUITE_P(Transports, CanRobotTest,
                         ::testing::Values(Transport::kSlcanPty, Transport::kMemory),
                         [](const auto& param_info) {
                           return param_info.param == Transport::kSlcanPty ? "SlcanPty" : "Memory";
                         });

// A node that answers with a result the decoder refuses (NaN progress), and then nothing.
TEST(CanRobot, AMalformedResultIsNamedInTheMalfunction) {
  auto [controller, node] = make_memory_can_pair();
  JobReport bad;
  bad.progress_m = std::numeric_limits<double>::quiet_NaN();
  for (const Message& m :
       {Message(JobAck{1, AckCode::kAccepted, 0}), Message(JobResult{1, bad, {}})}) {
    for (const CanFrame& f : encode(m)) ASSERT_TRUE(node->send(f).has_value());
  }
  CanRobot robot(*controller, {.ack_timeout_s = 0.05, .link_timeout_s = 0.05, .heartbeat_s = 0.05});
  const JobReport r = robot.execute(LiftHead{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error->kind, RobotErrorKind::kMalfunction);
  EXPECT_THAT(r.error->reason, HasSubstr("CAN link: no result of job 1"));
  EXPECT_THAT(r.error->reason,
              HasSubstr("malformed result 1: progress_m is not a finite number >= 0"));
  EXPECT_EQ(robot.stats().bad_input, 1U);
}

TEST(BusFaults, TheSpecificationIsReadAndNamedWhenWrong) {
  Result<BusFaults> f =
      parse_bus_faults("drop=3,7;garbage=2;silence=10+3;bus-off=12;late-ack=4@1.5;lose-result=5");
  ASSERT_TRUE(f.has_value()) << f.error().message;
  EXPECT_EQ(f->drop_frames, (std::vector<std::uint64_t>{3, 7}));
  EXPECT_EQ(f->lose_results, (std::vector<std::uint64_t>{5}));
  EXPECT_EQ(f->silence, (Silence{10, 3}));
  EXPECT_EQ(f->late_ack, (LateAck{4, 1.5}));
  std::ostringstream os;
  os << *f;
  EXPECT_EQ(*parse_bus_faults(os.str()), *f);
  EXPECT_THAT(parse_bus_faults("drop=x").error().message, HasSubstr("'drop=x'"));
  EXPECT_THAT(parse_bus_faults("fire=1").error().message, HasSubstr("unknown fault"));
  EXPECT_THAT(parse_bus_faults("drop-rate=2").error().message, HasSubstr("probability"));
}

}  // namespace
}  // namespace sewerplan::hal
