// SPDX-License-Identifier: MIT
// Issue 14's "ended at exit while not there", on the paper's test environment
// (datasets/ais-testbed): a go-to at the M10 end of P9 (4.243 m), from the start in P12. The plan
// ends with a pass at M10 from P11 into P9, a go-to of 0 m and a drive of 0 m back to M10.
// Fusion sends no job for a 0 m move; the executor took the plan's word for where the robot was
// and reported "mission ended at exit M10" while the robot stood in P9 facing away from M10.
#include <gtest/gtest.h>

#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

Mission go_to_the_m10_end_of_p9(const testing::AisTestbed& ais) {
  Mission mission = ais.mission;
  const PipeId p9 = *ais.map.find_pipe("P9");
  mission.tasks = {Task{.name = "end-of-p9",
                        .kind = TaskKind::kGoTo,
                        .place = PipeSpot{.pipe = p9, .offset_m = ais.map.pipe(p9).length_m}}};
  return mission;
}

// A robot whose first long drive to a place in a pipe stops 1 m short without an error (a wheel
// slipping on silt, say): its report says how far it got, and the plan no longer says where it
// is. (A drive to a manhole that the robot reports done ends at the manhole: core/job.h.)
class FirstDriveStopsShort final : public hal::Robot {
 public:
  explicit FirstDriveStopsShort(hal::Robot& robot) : robot_(robot) {}
  hal::JobReport execute(const Job& job) override {
    const auto* forward = std::get_if<DriveForward>(&job);
    if (!shortened_ && forward != nullptr && !forward->to_manhole && forward->distance_m > 2) {
      shortened_ = true;
      return robot_.execute(
          DriveForward{.speed_mps = forward->speed_mps, .distance_m = forward->distance_m - 1});
    }
    return robot_.execute(job);
  }
  hal::RobotStatus status() const override { return robot_.status(); }
  Result<void> reboot() override { return robot_.reboot(); }
  hal::BeaconState activate_beacon() override { return robot_.activate_beacon(); }
  void emergency_stop() override { robot_.emergency_stop(); }

 private:
  hal::Robot& robot_;
  bool shortened_ = false;
};

struct GoToP9 {
  testing::AisTestbed ais = testing::load_ais_testbed();
  Mission mission = go_to_the_m10_end_of_p9(ais);
  ManualClock clock;
  Replanner replanner{ais.map, mission, {.clock = &clock}};
  hal::SimRobot robot{ais.map, mission.profile,
                      hal::InPipe{std::get<domain::InPipe>(replanner.progress().position).pipe,
                                  std::get<domain::InPipe>(replanner.progress().position).offset_m,
                                  hal::Heading::kTowardsEnd1}};
  std::vector<Event> events;
  MissionReport run(hal::Robot& driven) {
    Executor executor(ais.map, replanner, driven);
    executor.subscribe([this](const Event& e) { events.push_back(e); });
    return executor.run();
  }
};

TEST(ExecutorIssue14, AMissionEndedAtAnExitHasTheRobotThere) {
  GoToP9 s;
  const MissionReport report = s.run(s.robot);
  ASSERT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_EQ(report.end, "exit M10") << report;
  EXPECT_EQ(report.tasks_done, (std::vector<std::string>{"end-of-p9"})) << report;
  // The simulator's ground truth: at M10's mouth of P9, not in P9 facing away from M10.
  const auto* at = std::get_if<hal::AtSlot>(&s.robot.pose());
  ASSERT_NE(at, nullptr) << hal::describe(s.robot.pose(), s.ais.map);
  EXPECT_EQ(s.ais.map.manhole(at->manhole).name, "M10");
}

TEST(ExecutorIssue14, ARobotThatIsNotWhereThePlanPutsItIsReplannedFromWhereItIs) {
  // A go-to 1 m from P9's far end, 3.24 m into it from M10: the drive there is to a place in the
  // pipe, not to a manhole.
  GoToP9 s;
  const PipeId p9 = *s.ais.map.find_pipe("P9");
  Mission mission = s.ais.mission;
  mission.tasks = {Task{.name = "into-p9",
                        .kind = TaskKind::kGoTo,
                        .place = PipeSpot{.pipe = p9, .offset_m = 1.0},
                        .final = true}};
  Replanner replanner{s.ais.map, mission, {.clock = &s.clock}};
  FirstDriveStopsShort robot(s.robot);
  Executor executor(s.ais.map, replanner, robot);
  executor.subscribe([&](const Event& e) { s.events.push_back(e); });
  const MissionReport report = executor.run();
  ASSERT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_EQ(report.replans, 1U) << report;
  EXPECT_EQ(report.tasks_done, (std::vector<std::string>{"into-p9"})) << report;
  // The simulator's ground truth: where the task is.
  const auto* in = std::get_if<hal::InPipe>(&s.robot.pose());
  ASSERT_NE(in, nullptr) << hal::describe(s.robot.pose(), s.ais.map);
  EXPECT_EQ(in->pipe, p9);
  EXPECT_NEAR(in->offset_m, 1.0, 1e-6);
  // The executor saw it after the short drive and planned again from there.
  bool noticed = false;
  for (const Event& e : s.events) {
    const auto* replan = std::get_if<PlanEvent>(&e.what);
    noticed = noticed || (replan != nullptr && replan->replan &&
                          replan->reason.starts_with("the robot is in pipe P9 at"));
  }
  EXPECT_TRUE(noticed);
}

}  // namespace
}  // namespace sewerplan::executor
