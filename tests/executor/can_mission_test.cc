// SPDX-License-Identifier: MIT
// Acceptance of the CAN issue (#7): a whole mission of the AIS test environment runs over SLCAN
// through a pseudo-terminal against the simulated node with the outcome and event log of the
// in-process simulated robot; each injected bus fault ends in the handling docs/can-protocol.md
// documents; and the candump log of a run replays to the same event log.
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/can/can_robot.h"
#include "sewerplan/hal/can/candump.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include "support/can_node.h"
#include "support/paths.h"

namespace sewerplan::executor {
namespace {

using ::testing::HasSubstr;
using MissionOutcome = MissionReport::Outcome;

struct CanRun {
  std::string report;  // MissionReport as printed
  MissionReport mission;
  std::string json_lines;
  hal::CanLinkStats link;
};

hal::SimPose start_of(const Replanner& replanner) {
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  return hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1};
}

CanRun run_on(const SewerMap& map, const Mission& mission, hal::Robot& robot, ManualClock& clock) {
  Replanner replanner(map, mission, {.clock = &clock});
  std::ostringstream json;
  CanRun run;
  Executor executor(map, replanner, robot);
  executor.subscribe(json_lines_writer(json));
  run.mission = executor.run();
  std::ostringstream report;
  report << run.mission;
  run.report = report.str();
  run.json_lines = json.str();
  return run;
}

CanRun in_process(const testing::AisTestbed& ais, const hal::FaultScenario& faults) {
  ManualClock clock;  // planning times of 0: runs compare equal
  Replanner probe(ais.map, ais.mission, {.clock = &clock});
  hal::SimRobot robot(ais.map, ais.mission.profile, start_of(probe), faults);
  return run_on(ais.map, ais.mission, robot, clock);
}

// Short timeouts for runs with bus faults, so that they do not make the tests slow.
hal::CanRobotOptions fast() {
  return {.ack_timeout_s = 0.15, .link_timeout_s = 0.3, .heartbeat_s = 0.05};
}
// Long ones for clean runs, which never wait for a timeout: a loaded machine cannot make them retry
// (a retry would not be in an in-process run's log, and the replay answers without delay).
hal::CanRobotOptions patient() { return {.ack_timeout_s = 5, .link_timeout_s = 10}; }

// Over SLCAN through a pty; `candump` gets the bus traffic when given.
CanRun over_can(const testing::AisTestbed& ais, const hal::FaultScenario& faults,
                const std::string& bus_faults = "", std::ostream* candump = nullptr) {
  const hal::CanRobotOptions options = bus_faults.empty() ? patient() : fast();
  ManualClock clock;
  Replanner probe(ais.map, ais.mission, {.clock = &clock});
  Result<hal::BusFaults> parsed = hal::parse_bus_faults(bus_faults);
  EXPECT_TRUE(parsed.has_value());
  testing::CanNodeThread node(ais.map, ais.mission.profile, start_of(probe), faults, *parsed,
                              testing::Transport::kSlcanPty);
  if (!node.ok()) return {};
  SteadyClock wall;
  std::optional<hal::RecordingCanBus> recording;
  if (candump != nullptr) recording.emplace(node.controller_bus(), *candump, wall);
  hal::CanBus& bus = recording ? static_cast<hal::CanBus&>(*recording) : node.controller_bus();
  hal::CanRobot robot(bus, options);
  const Result<void> up = robot.connect();
  EXPECT_TRUE(up.has_value()) << up.error().message;
  CanRun run = run_on(ais.map, ais.mission, robot, clock);
  run.link = robot.stats();
  return run;
}

hal::FaultScenario demo_faults(const SewerMap& map) {
  Diagnostics d;
  auto scenario =
      hal::read_faults(sewerplan::testing::dataset_path("ais-testbed/faults/demo.json"), map, d);
  EXPECT_TRUE(scenario.has_value()) << d.error_summary();
  return scenario.has_value() ? *scenario : hal::FaultScenario{};
}

hal::FaultScenario malfunction(const SewerMap& map, const char* kind) {
  Diagnostics d;
  auto f = hal::read_faults_json(std::string(R"({"format": "sewerplan-faults", "version": 1,
      "malfunctions": [{"at_job": 3, "kind": ")") +
                                     kind + "\"}]}",
                                 "m.json", map, d);
  EXPECT_TRUE(f.has_value()) << d.error_summary();
  return f.has_value() ? *f : hal::FaultScenario{};
}

TEST(CanMission, ThePapersMissionOverSlcanEqualsTheSimulatedRobotInProcess) {
  const auto ais = testing::load_ais_testbed();
  const CanRun local = in_process(ais, {});
  const CanRun bus = over_can(ais, {});
  EXPECT_EQ(bus.report, local.report);
  EXPECT_EQ(bus.json_lines, local.json_lines);
  EXPECT_EQ(bus.mission.tasks_done, (std::vector<std::string>{"sample", "inspect", "end"}));
  EXPECT_EQ(bus.link.retries, 0U);
}

TEST(CanMission, RobotFaultsCrossTheBusWithTheSameRecoveryAndReplanning) {
  const auto ais = testing::load_ais_testbed();
  const std::vector<hal::FaultScenario> scenarios{
      demo_faults(ais.map),
      malfunction(ais.map, "transient"),
      malfunction(ais.map, "permanent"),
      *hal::random_faults(ais.map,
                          {.seed = 7, .obstacle_rate_per_km = 40, .malfunction_rate_per_hour = 2}),
  };
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    const CanRun local = in_process(ais, scenarios[i]);
    const CanRun bus = over_can(ais, scenarios[i]);
    EXPECT_EQ(bus.report, local.report) << "scenario " << i;
    EXPECT_EQ(bus.json_lines, local.json_lines) << "scenario " << i;
  }
}

// Node frames: connect's status is 0-4; each job then takes an ack, a progress and a result of 8
// frames (more with a reason).
TEST(CanMission, LostFramesGarbageAndLateAcksAreRepairedWithoutChangingTheRun) {
  const auto ais = testing::load_ais_testbed();
  const CanRun local = in_process(ais, {});
  for (const char* spec :
       {"drop=5,16,40", "drop-rate=0.02;seed=3", "garbage=5,30", "late-ack=2@0.4"}) {
    const CanRun bus = over_can(ais, {}, spec);
    EXPECT_EQ(bus.report, local.report) << spec;
    EXPECT_EQ(bus.json_lines, local.json_lines) << spec;
    EXPECT_GE(bus.link.retries + bus.link.bad_input, 1U) << spec;
  }
}

// An acknowledgement later than all the JOB's sends (3 x the ack timeout; about 1.5 s with the
// defaults) ended the mission: the controller declared the link failed while the node drove the
// job, and the reboot that followed read "reboot failed: reboot failed:". docs/can-protocol.md
// says a late acknowledgement changes nothing: the controller waits for the job's result.
TEST(CanMission, AnAcknowledgementLaterThanEveryResendChangesNothing) {
  const auto ais = testing::load_ais_testbed();
  const CanRun local = in_process(ais, {});
  const CanRun bus = over_can(ais, {}, "late-ack=2@0.6");
  EXPECT_EQ(bus.report, local.report);
  EXPECT_EQ(bus.json_lines, local.json_lines);
}

TEST(CanMission, SilenceAndBusOffAreMalfunctionsThatARebootOverTheBusClears) {
  const auto ais = testing::load_ais_testbed();
  for (const char* spec : {"silence=4+3", "bus-off=4"}) {
    const CanRun bus = over_can(ais, {}, spec);
    EXPECT_EQ(bus.mission.outcome, MissionOutcome::kEnded) << spec;
    EXPECT_EQ(bus.mission.tasks_done, (std::vector<std::string>{"sample", "inspect", "end"}))
        << spec;
    EXPECT_EQ(bus.mission.recoveries, 1U) << spec;
    EXPECT_THAT(bus.json_lines, HasSubstr(R"("kind":"malfunction","reason":"CAN link: )"));
    EXPECT_THAT(bus.json_lines, HasSubstr(R"("phase":"reboot","ok":true)"));
  }
}

TEST(CanMission, ANodeThatFallsSilentForGoodEndsWithTheBeacon) {
  const auto ais = testing::load_ais_testbed();
  const CanRun bus = over_can(ais, {}, "silence=4+100000");
  EXPECT_EQ(bus.mission.outcome, MissionOutcome::kBeacon) << bus.report;
  EXPECT_THAT(bus.json_lines, HasSubstr("reboot failed: no answer over CAN"));
}

TEST(CanMission, TheCandumpLogOfARunReplaysToTheSameEventLog) {
  const auto ais = testing::load_ais_testbed();
  for (const hal::FaultScenario& faults : {hal::FaultScenario{}, demo_faults(ais.map)}) {
    std::stringstream log;
    const CanRun recorded = over_can(ais, faults, "", &log);
    Result<std::vector<hal::CandumpRecord>> records = hal::read_candump(log, "run.log");
    ASSERT_TRUE(records.has_value()) << records.error().message;
    EXPECT_GT(records->size(), 100U);
    hal::ReplayCanBus replay(*records, "run.log");
    hal::CanRobot robot(replay, fast());
    ASSERT_TRUE(robot.connect().has_value());
    ManualClock clock;
    const CanRun replayed = run_on(ais.map, ais.mission, robot, clock);
    EXPECT_EQ(replayed.json_lines, recorded.json_lines);
    EXPECT_EQ(replayed.report, recorded.report);
    EXPECT_EQ(replay.unsent(), 0U);
  }
}

}  // namespace
}  // namespace sewerplan::executor
