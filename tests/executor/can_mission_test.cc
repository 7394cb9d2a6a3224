// SPDX-License-Identifier: MIT
// Acceptance of the CAN issues (#7, #30): a whole mission of the AIS test environment runs over
// SLCAN through a pseudo-terminal against the simulated node with the outcome and event log of the
// in-process simulated robot; each injected bus fault ends in the handling docs/can-protocol.md
// documents; the candump log of a run replays to the same event log; and lost frames - at random
// (1, 5 and 20 %), each frame of a turn, a drive, a sample and a reboot alone, every copy of a
// job's result - end the mission as the loss-free run does (the same tasks, the same end).
#include <map>
#include <set>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/can/can_robot.h"
#include "sewerplan/hal/can/candump.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"
#include "sewerplan/hal/world_errors.h"

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

// The simulated robot of a run: in the map itself, or in a true world drawn from it (issue 29,
// hal/world_errors.h) with its sensing; the start and the faults are given on the map.
struct RobotSetup {
  const SewerMap* world = nullptr;
  hal::SimPose start;
  hal::FaultScenario faults;
  hal::SimOptions options;
};

RobotSetup setup_of(const testing::AisTestbed& ais, const hal::FaultScenario& faults,
                    const hal::TrueWorld* truth) {
  ManualClock clock;
  Replanner probe(ais.map, ais.mission, {.clock = &clock});
  if (truth == nullptr) return {&ais.map, start_of(probe), faults, {}};
  return {&truth->world, hal::world_pose(ais.map, *truth, start_of(probe)),
          hal::world_faults(ais.map, *truth, faults),
          hal::SimOptions{.sensing = hal::make_sensing(*truth)}};
}

CanRun in_process(const testing::AisTestbed& ais, const hal::FaultScenario& faults,
                  const hal::TrueWorld* truth = nullptr) {
  ManualClock clock;  // planning times of 0: runs compare equal
  const RobotSetup s = setup_of(ais, faults, truth);
  hal::SimRobot robot(*s.world, ais.mission.profile, s.start, s.faults, s.options);
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
                const std::string& bus_faults = "", std::ostream* candump = nullptr,
                const hal::TrueWorld* truth = nullptr) {
  const hal::CanRobotOptions options = bus_faults.empty() ? patient() : fast();
  ManualClock clock;
  Result<hal::BusFaults> parsed = hal::parse_bus_faults(bus_faults);
  EXPECT_TRUE(parsed.has_value());
  const RobotSetup s = setup_of(ais, faults, truth);
  testing::CanNodeThread node(*s.world, ais.mission.profile, s.start, s.faults, *parsed,
                              testing::Transport::kSlcanPty, 0.5, s.options);
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
  // The node never answered the beacon request: the report does not say the beacon is on, and the
  // cause is the link.
  EXPECT_EQ(bus.mission.beacon, hal::BeaconState::kUnconfirmed);
  EXPECT_EQ(bus.mission.beacon_cause, BeaconCause::kLink);
  EXPECT_THAT(bus.report, HasSubstr("beacon requested, unconfirmed (the robot did not answer)"));
  EXPECT_THAT(bus.report, ::testing::Not(HasSubstr("beacon on")));
  EXPECT_THAT(bus.json_lines, HasSubstr(R"("state":"unconfirmed")"));
  EXPECT_THAT(bus.json_lines, HasSubstr(R"("beacon_cause":"link","beacon":"unconfirmed")"));
}

// The controller's end of a bus, with every frame it sent and received kept.
class Tap final : public hal::CanBus {
 public:
  explicit Tap(hal::CanBus& bus) : bus_(bus) {}
  Result<void> send(const hal::CanFrame& frame) override {
    sent.push_back(frame);
    return bus_.send(frame);
  }
  Result<std::optional<hal::CanFrame>> receive(double timeout_s) override {
    Result<std::optional<hal::CanFrame>> in = bus_.receive(timeout_s);
    if (in.has_value() && in->has_value()) received.push_back(**in);
    return in;
  }
  Result<void> recover() override { return bus_.recover(); }
  std::string name() const override { return bus_.name(); }
  std::vector<hal::CanFrame> sent;
  std::vector<hal::CanFrame> received;

 private:
  hal::CanBus& bus_;
};

// The frames the controller sent and received.
struct Traffic {
  std::vector<hal::CanFrame> sent;
  std::vector<hal::CanFrame> received;
};

// Over the in-memory bus with short timeouts, so that many faulty runs stay quick (a timeout that
// a loaded machine makes expire early only adds a retry); `traffic` gets the frames when given.
CanRun over_memory(const testing::AisTestbed& ais, const hal::FaultScenario& faults,
                   const std::string& bus_faults, Traffic* traffic = nullptr,
                   const hal::TrueWorld* truth = nullptr) {
  ManualClock clock;
  Result<hal::BusFaults> parsed = hal::parse_bus_faults(bus_faults);
  EXPECT_TRUE(parsed.has_value()) << bus_faults;
  const RobotSetup s = setup_of(ais, faults, truth);
  testing::CanNodeThread node(*s.world, ais.mission.profile, s.start, s.faults, *parsed,
                              testing::Transport::kMemory, 0.05, s.options);
  Tap recording(node.controller_bus());
  hal::CanRobot robot(recording,
                      {.ack_timeout_s = 0.05, .link_timeout_s = 0.1, .heartbeat_s = 0.05});
  const Result<void> up = robot.connect();
  EXPECT_TRUE(up.has_value()) << bus_faults << ": " << up.error().message;
  CanRun run = run_on(ais.map, ais.mission, robot, clock);
  run.link = robot.stats();
  if (traffic != nullptr) *traffic = {recording.sent, recording.received};
  return run;
}

// The mission outcome: how it ended, where, and the tasks done.
void expect_same_outcome(const CanRun& bus, const CanRun& local, const std::string& what) {
  EXPECT_EQ(bus.mission.outcome, local.mission.outcome) << what << "\n" << bus.report;
  EXPECT_EQ(bus.mission.end, local.mission.end) << what;
  EXPECT_EQ(bus.mission.tasks_done, local.mission.tasks_done) << what;
  EXPECT_EQ(bus.mission.dropped, local.mission.dropped) << what;
}

// Every copy of one job's PROGRESS and RESULT is lost until the reboot that follows. The node did
// the job; the controller, which had not heard how far, sent it again from where it last heard of
// the robot: the node refused the turn ("not at slot 1 of a manhole") or the drive ("cannot drive
// forward into manhole ..."), the refusal counted as a malfunction, and two reboots later the
// healthy robot called for recovery (stuck). Each job of the mission in turn.
TEST(CanMission, AJobWhoseResultTheLinkLostGoesOnFromTheNodesOwnReport) {
  const auto ais = testing::load_ais_testbed();
  const CanRun local = in_process(ais, {});
  const std::size_t jobs = local.mission.jobs;
  ASSERT_GE(jobs, 10U);
  std::size_t recovered = 0;
  for (std::size_t job = 0; job < jobs; ++job) {
    const std::string spec = "lose-result=" + std::to_string(job);
    const CanRun bus = over_memory(ais, {}, spec);
    expect_same_outcome(bus, local, spec);
    EXPECT_THAT(bus.json_lines, HasSubstr("CAN link: no result of job")) << spec;
    EXPECT_THAT(bus.json_lines, ::testing::Not(HasSubstr("stuck"))) << spec;
    recovered += bus.mission.recoveries;
  }
  EXPECT_EQ(recovered, jobs);  // one reboot each
}

// 1 %, 5 % and 20 % of the node's frames lost at random, three seeds each.
TEST(CanMission, RandomFrameLossEndsTheMissionAsTheLossFreeRun) {
  const auto ais = testing::load_ais_testbed();
  const CanRun local = in_process(ais, {});
  for (const char* rate : {"0.01", "0.05", "0.2"}) {
    for (int seed = 1; seed <= 3; ++seed) {
      const std::string spec = std::string("drop-rate=") + rate + ";seed=" + std::to_string(seed);
      const CanRun bus = over_memory(ais, {}, spec);
      expect_same_outcome(bus, local, spec);
    }
  }
}

// Each frame the node sends for the first turn, drive and sample of the mission, and for the
// reboot after a transient malfunction, lost alone. Frames are numbered as the node counts them
// (its frames but heartbeats), read from the loss-free run's traffic.
TEST(CanMission, EachFrameOfATurnADriveASampleAndARebootLostAloneChangesNoOutcome) {
  const auto ais = testing::load_ais_testbed();
  for (const hal::FaultScenario& faults :
       {hal::FaultScenario{}, malfunction(ais.map, "transient")}) {
    const CanRun local = in_process(ais, faults);
    Traffic clean;
    const CanRun loss_free = over_memory(ais, faults, "", &clean);
    expect_same_outcome(loss_free, local, "no loss");
    // The job kind of each sequence number.
    std::map<std::uint8_t, std::size_t> kind_of;
    hal::MessageDecoder decoder;
    for (const hal::CanFrame& f : clean.sent) {
      if (std::optional<hal::Decoded> d = decoder.push(f)) {
        if (const auto* m = std::get_if<hal::Message>(&*d)) {
          if (const auto* job = std::get_if<hal::JobCommand>(m))
            kind_of[job->seq] = job->job.index();
        }
      }
    }
    // The node's frames of the first job of each kind wanted, and of the first reboot.
    const std::set<std::size_t> kinds{Job{TurnInManhole{}}.index(), Job{DriveForward{}}.index(),
                                      Job{TakeSample{}}.index()};
    constexpr std::size_t kReboot = std::variant_size_v<Job>;
    std::map<std::size_t, std::uint8_t> first_seq;  // job kind (or kReboot) -> its first seq
    std::vector<std::uint64_t> targets;
    std::uint64_t index = 0;
    for (const hal::CanFrame& f : clean.received) {
      const std::optional<hal::FrameId> id = hal::frame_id(f);
      if (!id || id->type == hal::MessageType::kNodeHeartbeat) continue;
      const std::uint64_t at = index++;
      std::size_t key = 0;
      if (id->type == hal::MessageType::kRebootResult) {
        key = kReboot;
      } else if (id->type == hal::MessageType::kAck || id->type == hal::MessageType::kProgress ||
                 id->type == hal::MessageType::kResult) {
        const auto kind = kind_of.find(id->seq);
        if (kind == kind_of.end() || !kinds.contains(kind->second)) continue;
        key = kind->second;
      } else {
        continue;
      }
      const auto [it, first] = first_seq.emplace(key, id->seq);
      if (it->second == id->seq) targets.push_back(at);
    }
    EXPECT_EQ(first_seq.size(), faults.malfunctions.empty() ? 3U : 4U);
    ASSERT_GE(targets.size(), 30U);
    for (const std::uint64_t frame : targets) {
      const std::string spec = "drop=" + std::to_string(frame);
      expect_same_outcome(over_memory(ais, faults, spec), local, spec);
    }
  }
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

// Issue 29: a robot in a world that is not the map, with slipping wheels, missed and false
// manholes, reports its odometry and what it saw at each manhole in the job's RESULT. Over SLCAN
// the run is the in-process run, event for event (the arrivals with their observed signatures).
hal::TrueWorld realistic_world(const testing::AisTestbed& ais, std::uint64_t seed) {
  const Result<hal::TrueWorld> truth =
      hal::make_true_world(ais.map, *hal::parse_world_errors("realistic"), seed);
  EXPECT_TRUE(truth.has_value());
  return truth.has_value() ? *truth : hal::TrueWorld{};
}

TEST(CanMission, IssueTwentyNineARunInARealisticWorldOverSlcanEqualsTheRunInProcess) {
  const auto ais = testing::load_ais_testbed();
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const hal::TrueWorld truth = realistic_world(ais, seed);
    const CanRun local = in_process(ais, {}, &truth);
    ASSERT_THAT(local.json_lines, HasSubstr("\"observed\":")) << "seed " << seed;
    const CanRun bus = over_can(ais, {}, "", nullptr, &truth);
    EXPECT_EQ(bus.report, local.report) << "seed " << seed;
    EXPECT_EQ(bus.json_lines, local.json_lines) << "seed " << seed;
    EXPECT_EQ(bus.link.retries, 0U);
  }
}

// The observation's frames lost on the way are repaired as any result frame (a RESULT_REQUEST;
// the copies fill the gaps), and a result the link lost until the reboot comes back with its
// observation (the node's kept RESULT): the run ends as the loss-free one.
TEST(CanMission, IssueTwentyNineLostObservationFramesChangeNoOutcome) {
  const auto ais = testing::load_ais_testbed();
  const hal::TrueWorld truth = realistic_world(ais, 2);
  const CanRun local = in_process(ais, {}, &truth);
  Traffic clean;
  expect_same_outcome(over_memory(ais, {}, "", &clean, &truth), local, "no loss");
  // The node's frames (as it counts them: heartbeats aside) of the first observed RESULT.
  std::vector<std::uint64_t> observation;
  std::optional<std::uint8_t> observed_seq;
  std::uint64_t index = 0;
  for (const hal::CanFrame& f : clean.received) {
    const std::optional<hal::FrameId> id = hal::frame_id(f);
    if (!id || id->type == hal::MessageType::kNodeHeartbeat) continue;
    const std::uint64_t at = index++;
    if (id->type != hal::MessageType::kResult) continue;
    if (id->index == 0 && !observed_seq && f.dlc == 6) observed_seq = id->seq;
    if (observed_seq == id->seq && id->index >= 7 && id->index != hal::kEndFrameIndex) {
      observation.push_back(at);  // the observation follows the 7 frames (header, numbers)
    }
  }
  ASSERT_GE(observation.size(), 6U);  // two slots at least
  for (const std::uint64_t frame :
       {observation.front(), observation[observation.size() / 2], observation.back()}) {
    const std::string spec = "drop=" + std::to_string(frame);
    const CanRun bus = over_memory(ais, {}, spec, nullptr, &truth);
    expect_same_outcome(bus, local, spec);
    EXPECT_GE(bus.link.retries + bus.link.timeouts, 1U) << spec;
  }
  // The job of that result, counted from 0 as the node runs them (loss-free: each job once).
  std::size_t job = 0;
  hal::MessageDecoder decoder;
  for (const hal::CanFrame& f : clean.sent) {
    const std::optional<hal::Decoded> d = decoder.push(f);
    const auto* m = d ? std::get_if<hal::Message>(&*d) : nullptr;
    const auto* command = m != nullptr ? std::get_if<hal::JobCommand>(m) : nullptr;
    if (command == nullptr) continue;
    if (command->seq == *observed_seq) break;
    ++job;
  }
  const std::string lose = "lose-result=" + std::to_string(job);
  const CanRun lost = over_memory(ais, {}, lose, nullptr, &truth);
  expect_same_outcome(lost, local, lose);
  EXPECT_THAT(lost.json_lines, HasSubstr("CAN link: no result of job")) << lose;
  const CanRun random = over_memory(ais, {}, "drop-rate=0.2;seed=1", nullptr, &truth);
  expect_same_outcome(random, local, "drop-rate=0.2");
}

}  // namespace
}  // namespace sewerplan::executor
