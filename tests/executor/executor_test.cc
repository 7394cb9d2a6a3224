// SPDX-License-Identifier: MIT
// The action controller on the simulated robot: the acceptance cases of the execute-and-replan
// issue, on the paper's test environment (datasets/ais-testbed). In that network MAKRO cannot turn
// from P3 into P4 at M5 (94 degrees), so P4 and P5 are the only ways between the two halves.
#include "sewerplan/executor/executor.h"

#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include "support/paths.h"
#include "support/small_map.h"

namespace sewerplan::executor {
namespace {

using MissionOutcome = MissionReport::Outcome;

struct SimRun {
  MissionReport report;
  std::vector<Event> events;
  std::string json_lines;
};

hal::FaultScenario faults(const SewerMap& map, const std::string& json) {
  Diagnostics d;
  auto f = hal::read_faults_json(json, "test.json", map, d);
  EXPECT_TRUE(f.has_value()) << d.error_summary();
  return f.has_value() ? *f : hal::FaultScenario{};
}

SimRun simulate(const SewerMap& map, const Mission& mission, const hal::FaultScenario& scenario,
                ExecutorOptions options = {}) {
  ManualClock clock;  // planning times of 0: runs compare equal
  Replanner replanner(map, mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(map, mission.profile,
                      hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1},
                      scenario);
  std::ostringstream json;
  SimRun run;
  Executor executor(map, replanner, robot, options);
  executor.subscribe(json_lines_writer(json));
  executor.subscribe([&run](const Event& e) { run.events.push_back(e); });
  run.report = executor.run();
  run.json_lines = json.str();
  EXPECT_EQ(robot.status().beacon_on, run.report.outcome == MissionOutcome::kBeacon);
  return run;
}

std::size_t count(const SimRun& run, std::string_view type) {
  std::size_t n = 0;
  for (const Event& e : run.events) n += type_name(e) == type ? 1U : 0U;
  return n;
}

bool dropped(const SimRun& run, const std::string& task, std::string_view reason_part) {
  for (const auto& [name, reason] : run.report.dropped) {
    if (name == task && reason.find(reason_part) != std::string::npos) return true;
  }
  return false;
}

TEST(Executor, WithoutFaultsThePapersMissionIsDoneAsPlanned) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run = simulate(ais.map, ais.mission, {});
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_EQ(run.report.tasks_done, (std::vector<std::string>{"sample", "inspect", "end"}));
  EXPECT_EQ(run.report.replans, 0U);
  EXPECT_EQ(run.report.beacon_cause, MissionReport::BeaconCause::kNone);
  EXPECT_NE(run.json_lines.find(R"("decision":"follow-plan","beacon_cause":"none")"),
            std::string::npos);
  EXPECT_NEAR(run.report.time_s, 585.4, 0.05);  // the plan's cost, to the robot's clock
  EXPECT_TRUE(run.report.battery_reserve_kept);
}

TEST(Executor, ABlockedPipeOnTheRouteIsDrivenAroundAndEveryTaskDone) {
  auto ais = testing::load_ais_testbed();
  ais.mission.tasks.erase(ais.mission.tasks.begin() + 1);  // no inspection of P4: P4 is a way
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
                          "obstacles": [{"pipe": "P4", "offset_m": 5.0, "kind": "permanent"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_EQ(run.report.tasks_done, (std::vector<std::string>{"sample", "end"}));
  EXPECT_TRUE(run.report.dropped.empty());
  EXPECT_EQ(run.report.replans, 1U);
  EXPECT_NE(run.report.end.find("pipe P9"), std::string::npos) << run.report.end;
  // Recovery tried its phases before the replan: two back-ups, one head lift; no push.
  EXPECT_EQ(count(run, "recovery"), 3U);
  EXPECT_EQ(run.json_lines.find("3: push"), std::string::npos);
}

TEST(Executor, ABlockageThatCutsATaskOffDropsItAndDoesTheRest) {
  const auto ais = testing::load_ais_testbed();
  Diagnostics d;
  const auto scenario = hal::read_faults(
      sewerplan::testing::dataset_path("ais-testbed/faults/demo.json"), ais.map, d);
  ASSERT_TRUE(scenario.has_value()) << d.error_summary();
  const SimRun run = simulate(ais.map, ais.mission, *scenario);
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_EQ(run.report.tasks_done, (std::vector<std::string>{"sample", "end"}));
  EXPECT_TRUE(dropped(run, "inspect", "pipe P4 is blocked at 4.95 m"));
  EXPECT_NE(run.report.end.find("pipe P9"), std::string::npos) << run.report.end;
  // The transient obstacle in P1 was cleared by lifting the head, without a replan.
  EXPECT_EQ(run.report.replans, 1U);
  EXPECT_NE(run.json_lines.find(R"("phase":"2: lift the head and retry","ok":true)"),
            std::string::npos);
}

TEST(Executor, WhenThePlannedEndIsCutOffTheNearestReachableExitIsTaken) {
  const auto ais = testing::load_ais_testbed();
  Diagnostics d;
  const auto scenario = hal::read_faults(
      sewerplan::testing::dataset_path("ais-testbed/faults/blocked-p5.json"), ais.map, d);
  ASSERT_TRUE(scenario.has_value()) << d.error_summary();
  const SimRun run = simulate(ais.map, ais.mission, *scenario);
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_EQ(run.report.end, "exit M4");  // back through M3: M4 is the nearest exit
  EXPECT_TRUE(dropped(run, "end", "end point cannot be reached"));
  EXPECT_TRUE(dropped(run, "sample", "no route"));
}

TEST(Executor, AStuckRobotSwitchesItsBeaconOn) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
                                  "malfunctions": [{"at_job": 3, "kind": "permanent"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kBeacon);
  EXPECT_NE(run.report.end.find("cannot move"), std::string::npos) << run.report.end;
  EXPECT_EQ(count(run, "beacon"), 1U);
  EXPECT_EQ(run.report.decision, PlanResponse::Decision::kStuck);
  EXPECT_EQ(run.report.beacon_cause, MissionReport::BeaconCause::kMalfunction);
  EXPECT_NE(run.json_lines.find(R"("decision":"stuck","beacon_cause":"malfunction")"),
            std::string::npos)
      << run.json_lines;
  // The robot's words were prefixed once more ("reboot failed: reboot failed: ...").
  EXPECT_NE(run.json_lines.find("reboot failed: permanent"), std::string::npos) << run.json_lines;
  EXPECT_EQ(run.json_lines.find("reboot failed: reboot failed"), std::string::npos)
      << run.json_lines;
}

// A cluster of transient malfunctions, the second and third timed while the robot reboots, used
// up the two reboots a job had, and the mission ended with the beacon, tasks left and a full
// battery. A reboot clears what strikes while it runs, and the budget bounds reboots in a row that
// did not help.
TEST(Executor, AClusterOfTransientMalfunctionsDoesNotEndTheMission) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "malfunctions": [{"at_time_s": 100, "kind": "transient"},
                           {"at_time_s": 125, "kind": "transient"},
                           {"at_time_s": 155, "kind": "transient"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report;
  EXPECT_EQ(run.report.tasks_done, (std::vector<std::string>{"sample", "inspect", "end"}))
      << run.report;
}

// Malfunctions that each strike after the robot has worked again since the last reboot: each is
// a fault of its own, not a robot that cannot stay up.
TEST(Executor, TransientMalfunctionsWithWorkBetweenThemAreEachRebootedThrough) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "malfunctions": [{"at_time_s": 100, "kind": "transient"},
                           {"at_time_s": 135, "kind": "transient"},
                           {"at_time_s": 170, "kind": "transient"},
                           {"at_time_s": 205, "kind": "transient"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report;
  EXPECT_EQ(run.report.tasks_done, (std::vector<std::string>{"sample", "inspect", "end"}))
      << run.report;
  EXPECT_EQ(run.report.recoveries, 4U) << run.report;
}

TEST(Executor, ATransientMalfunctionIsRebootedAndTheMissionGoesOn) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
                                  "malfunctions": [{"at_job": 3, "kind": "transient"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_EQ(run.report.tasks_done, (std::vector<std::string>{"sample", "inspect", "end"}));
  EXPECT_EQ(run.report.replans, 0U);
  EXPECT_EQ(run.report.recoveries, 1U);
  EXPECT_NE(run.json_lines.find(R"("phase":"reboot","ok":true)"), std::string::npos);
}

TEST(Executor, ATransientObstacleIsClearedWithoutAReplan) {
  const auto ais = testing::load_ais_testbed();
  for (const char* kind : {"transient_lift", "transient_push"}) {
    ExecutorOptions options;
    options.recovery.push_allowed = std::string(kind) == "transient_push";
    const SimRun run =
        simulate(ais.map, ais.mission,
                 faults(ais.map, std::string(R"({"format": "sewerplan-faults", "version": 1,
                    "obstacles": [{"pipe": "P1", "offset_m": 3.0, "kind": ")") +
                                     kind + "\"}]}"),
                 options);
    EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << kind;
    EXPECT_EQ(run.report.replans, 0U) << kind;
    EXPECT_EQ(run.report.tasks_done.size(), 3U) << kind;
    EXPECT_EQ(run.report.recoveries, 1U) << kind;
  }
}

TEST(Executor, ABatteryRunningLowSendsTheRobotToAnExitInsteadOfTheNextTask) {
  const auto ais = testing::load_ais_testbed();
  // makro-1.1 has 240 Wh and keeps 20% (48 Wh); this battery has 60 Wh: 12 Wh to use, and the
  // whole mission needs 19.5 Wh.
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
                                               "battery_wh": 60})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_GE(run.report.replans, 1U);
  EXPECT_NE(run.json_lines.find("battery low"), std::string::npos);
  EXPECT_LT(run.report.tasks_done.size(), 2U);
  EXPECT_TRUE(run.report.battery_reserve_kept) << run.report;
}

TEST(Executor, ADangerousPassageIsClosedAndAvoided) {
  const auto ais = testing::load_ais_testbed();
  // M6 from P5 (slot 3) into P6 (slot 4): the way to the sample.
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
                                  "danger": [{"manhole": "M6", "from_slot": 3, "to_slot": 4}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded);
  EXPECT_GE(run.report.replans, 1U);
  EXPECT_NE(run.json_lines.find(R"("kind":"danger")"), std::string::npos);
}

// Found by a fault campaign (docs/campaign.md, AIS, seed 1, run 0): the only passage on from the
// mouth of P10 in M8 is dangerous. Backing out into P10 lets the robot drive back to an exit; left
// at the mouth, it could only call for recovery.
TEST(Executor, ARobotBacksOutOfAManholeWithADangerousPassage) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "obstacles": [{"pipe": "P4", "offset_m": 0.63, "kind": "permanent"}],
          "danger": [{"manhole": "M8", "from_slot": 1, "to_slot": 2}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report;
  EXPECT_EQ(run.report.end.rfind("exit ", 0), 0U) << run.report;
  EXPECT_NE(run.json_lines.find("back out of the manhole"), std::string::npos);
  EXPECT_NE(run.json_lines.find(R"("type":"failure","kind":"dangerous passage","manhole":"M8")"),
            std::string::npos)
      << run.json_lines;
}

// Found by a fault campaign (AIS, seed 3, run 26): after backing out of M6 the robot passes into
// P10 and turns back at its mouth with its front towards P10; the second dangerous passage must
// send it forward into P10, and the simulated robot must keep that facing at the mouth.
TEST(Executor, ARobotFacingThePipeBacksOutForward) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "danger": [{"manhole": "M6", "from_slot": 1, "to_slot": 4},
                     {"manhole": "M6", "from_slot": 3, "to_slot": 4}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report << run.json_lines;
  EXPECT_EQ(run.json_lines.find("malfunction"), std::string::npos) << run.json_lines;
  EXPECT_NE(run.json_lines.find("DriveForward(0.30 m/s, 0.30 m)"), std::string::npos)
      << run.json_lines;
}

// Found by a fault campaign (AIS, seed 1, run 186): a danger spot 2.4 cm beyond the sample point
// W1 (P6 at 3.00 m). The robot stops short of it, before W1, so the sample cannot be taken from
// this side; taking the danger to be where the robot stopped lets the Replanner see that, rather
// than send the robot to W1 again and again.
TEST(Executor, ATaskJustShortOfADangerIsNotTriedForever) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "danger": [{"pipe": "P6", "offset_m": 3.024}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report;
  EXPECT_LE(run.report.replans, 3U) << run.report;
}

// Found by a fault campaign (AIS, seed 2, hard rates, run 125): recovery cleared one obstacle and
// the retried drive met a second one further on, which was taken to be the first one staying.
// Each obstacle gets recovery of its own.
TEST(Executor, ASecondObstacleBehindAClearedOneGetsItsOwnRecovery) {
  const auto ais = testing::load_ais_testbed();
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "obstacles": [{"pipe": "P1", "offset_m": 3.0, "kind": "transient_lift"},
                        {"pipe": "P1", "offset_m": 6.0, "kind": "transient_lift"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report;
  EXPECT_EQ(run.report.replans, 0U) << run.report;
  EXPECT_EQ(run.report.tasks_done.size(), 3U) << run.report;
  EXPECT_EQ(run.report.recoveries, 2U) << run.report;
}

// Found by a fault campaign (AIS, seed 2, hard rates, run 253): a transient malfunction while
// lifting the head left the robot "stuck". A reboot clears it, and recovery goes on.
TEST(Executor, ATransientMalfunctionDuringRecoveryIsRebootedThrough) {
  const auto ais = testing::load_ais_testbed();
  // Job 7 is the head lift of phase 2 (jobs: drive, pass, drive into the obstacle, two backups
  // and retries).
  const SimRun run =
      simulate(ais.map, ais.mission, faults(ais.map, R"({"format": "sewerplan-faults", "version": 1,
          "obstacles": [{"pipe": "P1", "offset_m": 3.0, "kind": "transient_lift"}],
          "malfunctions": [{"at_job": 7, "kind": "transient"}]})"));
  EXPECT_EQ(run.report.outcome, MissionOutcome::kEnded) << run.report;
  EXPECT_EQ(run.report.replans, 0U) << run.report;
  EXPECT_NE(run.json_lines.find(R"("job":"LiftHead","progress_m":0.0,"ok":false)"),
            std::string::npos)
      << run.json_lines;
  EXPECT_NE(run.json_lines.find(R"("phase":"2: lift the head and retry","ok":true)"),
            std::string::npos);
}

TEST(Executor, TheSameFaultsGiveTheSameRun) {
  const auto ais = testing::load_ais_testbed();
  auto scenario = hal::random_faults(
      ais.map, {.seed = 7, .obstacle_rate_per_km = 40, .malfunction_rate_per_hour = 2});
  ASSERT_TRUE(scenario.has_value());
  const SimRun a = simulate(ais.map, ais.mission, *scenario);
  const SimRun b = simulate(ais.map, ais.mission, *scenario);
  EXPECT_EQ(a.json_lines, b.json_lines);
  EXPECT_FALSE(a.json_lines.empty());
}

// Every plan the executor follows passed the validator (it checks each one before running it): no
// run ends with an invalid plan, over many random fault scenarios.
TEST(Executor, RandomFaultsNeverCrashHangOrBreakTheReserve) {
  const auto ais = testing::load_ais_testbed();
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    auto scenario = hal::random_faults(ais.map, {.seed = seed,
                                                 .obstacle_rate_per_km = 60,
                                                 .transient_share = 0.5,
                                                 .danger_rate_per_km = 10,
                                                 .dangerous_passage_share = 0.05,
                                                 .malfunction_rate_per_hour = 3});
    ASSERT_TRUE(scenario.has_value());
    const SimRun run = simulate(ais.map, ais.mission, *scenario);
    EXPECT_EQ(run.report.end.find("not valid"), std::string::npos) << seed << ": " << run.report;
    EXPECT_TRUE(run.report.battery_reserve_kept) << seed << ": " << run.report;
  }
}

// A robot at a mouth of a manhole with no way on through it for its limits (here a 122 degree
// turn, beyond makro-1.1's 90) is still at the end of the pipe it came out of, and drives both
// ways: it backs into that pipe and leaves by the exit behind it, rather than calling for
// recovery (the planner has no move from a mouth back into its own pipe).
TEST(Executor, ARobotAtAMouthWithNoWayOnBacksIntoThePipeItCameFrom) {
  const SewerMap map = testing::SmallMap()
                           .manhole("M1", 0, 0, /*exit=*/true)
                           .manhole("M2", 10, 0)
                           .manhole("M3", 5, 8)
                           .pipe("P1", "M1", "M2")
                           .pipe("P2", "M2", "M3")
                           .build();
  const ManholeId m2 = *map.find_manhole("M2");
  ManualClock clock;
  Replanner replanner(map, testing::small_mission(map, "P1"), {.clock = &clock});
  domain::MissionProgress at_mouth = replanner.progress();
  at_mouth.position = domain::AtSlot{m2, SlotIndex{0}};  // out of P1 into M2
  ASSERT_TRUE(replanner.update(at_mouth, 1).has_value());
  hal::SimRobot robot(map, replanner.mission().profile,
                      hal::AtSlot{m2, SlotIndex{0}, hal::Facing::kIntoManhole}, {});
  Executor executor(map, replanner, robot);
  std::vector<std::string> replans;
  executor.subscribe([&](const Event& e) {
    if (const auto* plan = std::get_if<PlanEvent>(&e.what); plan != nullptr && plan->replan)
      replans.push_back(plan->reason);
  });
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionOutcome::kEnded) << report.end;
  EXPECT_EQ(report.end, "exit M1");
  ASSERT_EQ(replans.size(), 1U);
  EXPECT_EQ(replans.front(), "no way on through M2 from slot 1: the robot backs into P1");
}

}  // namespace
}  // namespace sewerplan::executor
