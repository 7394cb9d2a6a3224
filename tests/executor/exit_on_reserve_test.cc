// SPDX-License-Identifier: MIT
// Issue 30: the battery reserve is the last way out, not a wall. When a search proves that no exit
// can be reached above the reserve, the Replanner sends the robot to the nearest exit it can reach
// on the charge left (exit-on-reserve), and calls for recovery only when not even that exit can be
// reached. On the paper's test environment (datasets/ais-testbed).
#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

using Decision = PlanResponse::Decision;

// The energy of the way from the mission's start to its nearest exit, every task left aside.
double nearest_exit_wh(const SewerMap& map, Mission mission) {
  mission.tasks.clear();
  mission.battery_reserve_fraction = 0;
  Replanner replanner(map, mission);
  const PlanResponse r = replanner.plan();
  EXPECT_TRUE(has_plan(r.decision)) << r.reason;
  return r.energy_wh;
}

// The paper's mission from its start, with `used_wh` of the battery already spent.
domain::MissionProgress spent(const SewerMap& map, const Mission& mission, double used_wh) {
  domain::MissionProgress p = domain::initial_progress(mission, map);
  p.energy_used_wh = used_wh;
  return p;
}

TEST(ExitOnReserve, TheNameIsStableAndItCarriesAPlanWithoutTheBeacon) {
  EXPECT_EQ(to_string(Decision::kExitOnReserve), "exit-on-reserve");
  EXPECT_EQ(parse_decision("exit-on-reserve"), Decision::kExitOnReserve);
  EXPECT_TRUE(has_plan(Decision::kExitOnReserve));
  EXPECT_FALSE(calls_beacon(Decision::kExitOnReserve));
}

TEST(ExitOnReserve, NoExitAboveTheReserveHeadsForTheNearestExitOnItIssue30) {
  const auto ais = testing::load_ais_testbed();
  const double exit_wh = nearest_exit_wh(ais.map, ais.mission);
  ASSERT_GT(exit_wh, 0);
  const double battery_wh = ais.mission.profile.battery_wh;
  const double reserve_wh = battery_wh * ais.mission.battery_reserve_fraction;
  ASSERT_LT(exit_wh, reserve_wh);  // so that half the way fits above the reserve, all of it not
  // Above the reserve half the way out is left; on the whole charge left, the way and more.
  const double used_wh = battery_wh - reserve_wh - exit_wh / 2;
  Replanner replanner(ais.map, ais.mission);
  ASSERT_TRUE(replanner.update(spent(ais.map, ais.mission, used_wh), 1).has_value());
  const PlanResponse r = replanner.plan("battery low");
  ASSERT_EQ(r.decision, Decision::kExitOnReserve) << r.reason;
  EXPECT_NE(r.reason.find("no exit can be reached above the battery reserve"), std::string::npos)
      << r.reason;
  EXPECT_NEAR(r.energy_wh, exit_wh, 1e-6);
  EXPECT_LE(r.energy_wh, battery_wh - used_wh);
  EXPECT_TRUE(replanner.on_reserve());
  EXPECT_DOUBLE_EQ(replanner.reserve_fraction(), ais.mission.battery_reserve_fraction);
  // Every task left is dropped, each saying why.
  EXPECT_EQ(r.goals, std::vector<TaskId>{});
  ASSERT_EQ(r.newly_dropped.size(), ais.mission.tasks.size());
  // The end point first (no way there), then the rest for the way out.
  for (const auto& d : r.newly_dropped) {
    if (ais.mission.task(d.task).final) continue;
    EXPECT_NE(d.reason.find("no exit can be reached above the battery reserve"), std::string::npos)
        << d.reason;
  }
  // The plan is a valid one on the mission as the Replanner now sees it (no reserve), from where
  // the robot is, and it ends at an exit.
  domain::MissionProgress start = replanner.progress();
  for (const auto& d : replanner.dropped()) start.done[d.task.index()] = true;
  const auto report = domain::validate_plan(r.plan, ais.map, replanner.mission(), start);
  EXPECT_TRUE(report.valid) << report.error;
  EXPECT_EQ(r.end.rfind("exit ", 0), 0U) << r.end;
  // A later replan (another blockage on the way out) is on the reserve too.
  const PlanResponse again = replanner.plan("again");
  EXPECT_EQ(again.decision, Decision::kExitOnReserve) << again.reason;
}

TEST(ExitOnReserve, TheBeaconOnlyWhenNotEvenTheReserveReachesAnExitIssue30) {
  const auto ais = testing::load_ais_testbed();
  const double exit_wh = nearest_exit_wh(ais.map, ais.mission);
  const double battery_wh = ais.mission.profile.battery_wh;
  // Half the way out is all the charge left.
  Replanner replanner(ais.map, ais.mission);
  ASSERT_TRUE(
      replanner.update(spent(ais.map, ais.mission, battery_wh - exit_wh / 2), 1).has_value());
  const PlanResponse r = replanner.plan("battery low");
  EXPECT_EQ(r.decision, Decision::kCallForRecovery) << r.reason;
  EXPECT_NE(r.reason.find("not even on the battery reserve"), std::string::npos) << r.reason;
  EXPECT_FALSE(replanner.on_reserve());
  // The world model keeps its reserve: nothing was dropped for a way out that does not exist.
  EXPECT_DOUBLE_EQ(replanner.mission().battery_reserve_fraction,
                   ais.mission.battery_reserve_fraction);
}

TEST(ExitOnReserve, ThePaperEraBaselineKeepsTheReserveAsAWall) {
  const auto ais = testing::load_ais_testbed();
  const double exit_wh = nearest_exit_wh(ais.map, ais.mission);
  const double battery_wh = ais.mission.profile.battery_wh;
  const double used_wh = battery_wh * (1 - ais.mission.battery_reserve_fraction) - exit_wh / 2;
  Replanner replanner(ais.map, ais.mission, {.goals = ReplannerOptions::Goals::kPaperBaseline});
  (void)replanner.plan();
  ASSERT_TRUE(replanner.update(spent(ais.map, ais.mission, used_wh), 1).has_value());
  const PlanResponse r = replanner.plan("battery low");
  EXPECT_EQ(r.decision, Decision::kCallForRecovery) << r.reason;
}

// A battery so small that from the start no exit is reachable above the reserve: the robot goes
// out on the reserve, says so with a "reserve" event, and the mission ends at an exit, not with
// the beacon.
TEST(ExitOnReserve, TheExecutorDrivesOutOnTheReserveAndReportsItIssue30) {
  auto ais = testing::load_ais_testbed();
  const double exit_wh = nearest_exit_wh(ais.map, ais.mission);
  // The way out needs all of the 80 % above the reserve and a quarter of the reserve more.
  ais.mission.profile.battery_wh = exit_wh / 0.85;
  ManualClock clock;
  Replanner replanner(ais.map, ais.mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(ais.map, ais.mission.profile,
                      hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1}, {});
  Executor executor(ais.map, replanner, robot);
  std::vector<Event> events;
  executor.subscribe([&](const Event& e) { events.push_back(e); });
  std::ostringstream json;
  executor.subscribe(json_lines_writer(json));
  const MissionReport report = executor.run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_EQ(report.decision, Decision::kExitOnReserve) << report;
  EXPECT_EQ(report.beacon_cause, BeaconCause::kNone);
  EXPECT_TRUE(report.exit_on_reserve);
  EXPECT_FALSE(report.battery_reserve_kept);  // spent, on purpose
  EXPECT_GE(robot.status().battery_wh, 0);
  EXPECT_EQ(report.end.rfind("exit ", 0), 0U) << report.end;
  // The reserve event comes right after the plan that decided it.
  // log_plan writes the drops before the plan: the plan event is after them.
  std::size_t at = 0;
  while (at < events.size() && !std::holds_alternative<PlanEvent>(events[at].what)) ++at;
  ASSERT_LT(at + 1, events.size());
  EXPECT_EQ(std::get<PlanEvent>(events[at].what).decision, Decision::kExitOnReserve);
  const auto* reserve = std::get_if<ReserveEvent>(&events[at + 1].what);
  ASSERT_NE(reserve, nullptr) << type_name(events[at + 1]);
  EXPECT_EQ(reserve->end, report.end);
  EXPECT_NEAR(reserve->energy_wh, exit_wh, 1e-6);
  EXPECT_NEAR(reserve->left_wh, ais.mission.profile.battery_wh, 1e-9);
  EXPECT_NEAR(reserve->reserve_wh,
              ais.mission.profile.battery_wh * ais.mission.battery_reserve_fraction, 1e-9);
  // The log names it, and reads back.
  EXPECT_NE(json.str().find("\"type\":\"reserve\""), std::string::npos);
  Diagnostics d;
  const auto read = read_event_log(json.str(), "reserve.jsonl", d);
  ASSERT_TRUE(read.has_value()) << d.error_summary();
  std::size_t reserves = 0;
  for (const Event& e : *read) reserves += std::holds_alternative<ReserveEvent>(e.what) ? 1U : 0U;
  EXPECT_EQ(reserves, 1U);
  // The report says the reserve was spent on the way out.
  std::ostringstream text;
  text << report;
  EXPECT_NE(text.str().find("the way out was on the reserve"), std::string::npos) << text.str();
}

}  // namespace
}  // namespace sewerplan::executor
