// SPDX-License-Identifier: MIT
// Why the beacon is on (MissionReport::BeaconCause) comes from the cause the robot typed on its
// error (hal::RobotErrorCause), not from the words of its reason: through the simulated robot, over
// CAN (the in-memory bus, the cause crossing in the RESULT's outcome code), and with every reason
// reworded to words that say something else, the beacon's cause is the same.
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/can/can_robot.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include "support/can_node.h"

namespace sewerplan::executor {
namespace {

using Cause = MissionReport::BeaconCause;
using MissionOutcome = MissionReport::Outcome;

// A robot whose every error reason (and a failed reboot's message) reads `words` (unless empty):
// what a robot of another make, or a firmware update, might say. Everything else passes through;
// the errors' causes are kept in `causes`.
class Rewording final : public hal::Robot {
 public:
  Rewording(hal::Robot& robot, std::string words) : robot_(robot), words_(std::move(words)) {}
  hal::JobReport execute(const Job& job) override { return reword(robot_.execute(job)); }
  hal::RobotStatus status() const override { return robot_.status(); }
  Result<void> reboot() override {
    Result<void> r = robot_.reboot();
    if (r.has_value() || words_.empty()) return r;
    return Error{r.error().code, words_};
  }
  std::optional<hal::JobReport> recovered_report() override {
    std::optional<hal::JobReport> r = robot_.recovered_report();
    if (r) r = reword(std::move(*r));
    return r;
  }
  hal::BeaconState activate_beacon() override { return robot_.activate_beacon(); }
  void emergency_stop() override { robot_.emergency_stop(); }

  std::vector<hal::RobotErrorCause> causes;

 private:
  hal::JobReport reword(hal::JobReport r) {
    if (!r.error) return r;
    causes.push_back(r.error->cause);
    if (!words_.empty()) r.error->reason = words_;
    return r;
  }
  hal::Robot& robot_;
  std::string words_;
};

// Words each of which the executor once took for a cause of its own ("CAN link", "malfunction",
// "reboot failed", "battery empty"), and words that name none.
const std::vector<std::string> kRewordings{"", "CAN link: lost", "permanent malfunction",
                                           "reboot failed: battery empty", "obstacle ahead"};

struct MissionRun {
  MissionReport report;
  std::string log;
  std::vector<hal::RobotErrorCause> causes;  // of the robot's errors, in order
};

MissionRun run_mission(const testing::AisTestbed& ais, hal::Robot& robot,
                       const std::string& words) {
  ManualClock clock;
  Replanner replanner(ais.map, ais.mission, {.clock = &clock});
  Rewording reworded(robot, words);
  Executor executor(ais.map, replanner, reworded);
  MissionRun run;
  run.report = executor.run();
  run.causes = reworded.causes;
  std::ostringstream text;
  text << run.report;
  run.log = text.str();
  return run;
}

hal::SimPose start_of(const testing::AisTestbed& ais) {
  ManualClock clock;
  const Replanner probe(ais.map, ais.mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(probe.progress().position);
  return hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1};
}

hal::FaultScenario permanent_malfunction() {
  hal::FaultScenario faults;
  faults.malfunctions.push_back(hal::Malfunction{hal::AtJob{3}, hal::MalfunctionKind::kPermanent});
  return faults;
}

TEST(BeaconCause, ThroughTheSimulatedRobotWhateverItsWords) {
  const auto ais = testing::load_ais_testbed();
  for (const std::string& words : kRewordings) {
    SCOPED_TRACE("reworded: '" + words + "'");
    hal::SimRobot robot(ais.map, ais.mission.profile, start_of(ais), permanent_malfunction());
    const MissionRun run = run_mission(ais, robot, words);
    EXPECT_EQ(run.report.outcome, MissionOutcome::kBeacon) << run.log;
    EXPECT_EQ(run.report.beacon_cause, Cause::kMalfunction) << run.log;
  }
}

// Short timeouts and one attempt: the node is in memory, on a thread of its own, and a link that
// fails for good is given up at once (a timeout that a loaded machine causes sooner is the link
// failing sooner: the same cause).
hal::CanRobotOptions quick() {
  return {.ack_timeout_s = 0.05, .link_timeout_s = 0.1, .attempts = 1, .heartbeat_s = 0.02};
}

MissionRun over_can(const testing::AisTestbed& ais, hal::FaultScenario faults,
                    const std::string& bus_faults, const std::string& words) {
  Result<hal::BusFaults> parsed = hal::parse_bus_faults(bus_faults);
  EXPECT_TRUE(parsed.has_value());
  testing::CanNodeThread node(ais.map, ais.mission.profile, start_of(ais), std::move(faults),
                              parsed.has_value() ? *parsed : hal::BusFaults{},
                              testing::Transport::kMemory, 0.02);
  if (!node.ok()) return {};
  hal::CanRobot robot(node.controller_bus(), quick());
  const Result<void> up = robot.connect();
  EXPECT_TRUE(up.has_value()) << up.error().message;
  return run_mission(ais, robot, words);
}

TEST(BeaconCause, OverCanTheCauseCrossesInTheResult) {
  const auto ais = testing::load_ais_testbed();
  for (const std::string& words : {std::string(), std::string("CAN link: lost")}) {
    SCOPED_TRACE("reworded: '" + words + "'");
    const MissionRun run = over_can(ais, permanent_malfunction(), "", words);
    EXPECT_EQ(run.report.outcome, MissionOutcome::kBeacon) << run.log;
    EXPECT_EQ(run.report.beacon_cause, Cause::kMalfunction) << run.log;
    // The node's robot said "fault" (code 0x31), not only "malfunction" (code 3).
    EXPECT_EQ(run.causes,
              std::vector<hal::RobotErrorCause>(run.causes.size(), hal::RobotErrorCause::kFault));
    EXPECT_FALSE(run.causes.empty());
  }
}

TEST(BeaconCause, OverCanALinkThatFailsForGoodIsTheLink) {
  const auto ais = testing::load_ais_testbed();
  // In the robot's words (can_mission_test.cc) and in words that say otherwise.
  const MissionRun run = over_can(ais, {}, "silence=4+100000", "permanent malfunction");
  EXPECT_EQ(run.report.outcome, MissionOutcome::kBeacon) << run.log;
  EXPECT_EQ(run.report.beacon_cause, Cause::kLink) << run.log;
  ASSERT_FALSE(run.causes.empty());
  EXPECT_EQ(run.causes.back(), hal::RobotErrorCause::kLink);
}

// A robot that, from its `from`th job on, fails every job with `cause`, and whose reboot works or
// fails as told: each malfunction's cause against the beacon's.
class FailingFrom final : public hal::Robot {
 public:
  FailingFrom(hal::Robot& robot, std::size_t from, hal::RobotErrorCause cause, bool reboot_works)
      : robot_(robot), from_(from), cause_(cause), reboot_works_(reboot_works) {}
  hal::JobReport execute(const Job& job) override {
    if (jobs_++ < from_) return robot_.execute(job);
    return {.error = hal::RobotError{cause_, "no words"}};
  }
  hal::RobotStatus status() const override { return robot_.status(); }
  Result<void> reboot() override {
    if (reboot_works_) return {};
    return Error{ErrorCode::kIo, "no words"};
  }
  hal::BeaconState activate_beacon() override { return robot_.activate_beacon(); }
  void emergency_stop() override {}

 private:
  hal::Robot& robot_;
  std::size_t from_;
  std::size_t jobs_ = 0;
  hal::RobotErrorCause cause_;
  bool reboot_works_;
};

TEST(BeaconCause, EachMalfunctionCauseGivesItsBeaconCause) {
  const auto ais = testing::load_ais_testbed();
  struct Case {
    hal::RobotErrorCause cause;
    Cause rebooted;  // the reboots work, and the job fails after every one
    Cause reboot_fails;
  };
  const std::vector<Case> cases{
      {hal::RobotErrorCause::kFault, Cause::kMalfunction, Cause::kMalfunction},
      {hal::RobotErrorCause::kBatteryEmpty, Cause::kMalfunction, Cause::kMalfunction},
      {hal::RobotErrorCause::kOtherMalfunction, Cause::kMalfunction, Cause::kMalfunction},
      {hal::RobotErrorCause::kLink, Cause::kLink, Cause::kLink},
      // A job the robot cannot run: the robot is held, not broken, and no reboot is tried (one
      // changes neither where the robot is nor what the job asks).
      {hal::RobotErrorCause::kInvalidJob, Cause::kStuck, Cause::kStuck},
      {hal::RobotErrorCause::kNotAtStart, Cause::kStuck, Cause::kStuck},
      // A stop: held too; a reboot that fails is a malfunction.
      {hal::RobotErrorCause::kEmergencyStop, Cause::kStuck, Cause::kMalfunction},
  };
  for (const Case& c : cases) {
    for (const bool reboot_works : {true, false}) {
      SCOPED_TRACE(std::string(hal::to_string(c.cause)) + (reboot_works ? "" : ", reboot fails"));
      hal::SimRobot sim(ais.map, ais.mission.profile, start_of(ais));
      FailingFrom robot(sim, 2, c.cause, reboot_works);
      const MissionRun run = run_mission(ais, robot, "");
      EXPECT_EQ(run.report.outcome, MissionOutcome::kBeacon) << run.log;
      EXPECT_EQ(run.report.beacon_cause, reboot_works ? c.rebooted : c.reboot_fails) << run.log;
    }
  }
}

}  // namespace
}  // namespace sewerplan::executor
