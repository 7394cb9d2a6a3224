// SPDX-License-Identifier: MIT
// Issue 14's livelock, on the paper's test environment (datasets/ais-testbed): a task point a
// hair beyond where the robot stops for a danger spot. The robot cannot get there (it keeps its
// clearance), yet the danger, taken to be 1 mm ahead of where it stopped, leaves the point on its
// side: each replan gave the plan that had just failed, 100 times, and then the beacon.
#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

TEST(ReplannerIssue14, ATaskJustBeyondADangerSpotIsDroppedInsteadOfReplannedForever) {
  const auto ais = testing::load_ais_testbed();
  // W1, the sample, is in P6 at 3.0 m; the robot comes from M6 (P6's end 0). It stops 5 cm
  // before the danger: 0.1 mm before W1.
  Diagnostics d;
  const auto faults = hal::read_faults_json(R"({"format": "sewerplan-faults", "version": 1,
      "danger": [{"pipe": "P6", "offset_m": 3.0499}]})",
                                            "livelock.json", ais.map, d);
  ASSERT_TRUE(faults.has_value()) << d.error_summary();
  ManualClock clock;
  Replanner replanner(ais.map, ais.mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(ais.map, ais.mission.profile,
                      hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1}, *faults);
  const MissionReport report = Executor(ais.map, replanner, robot).run();
  EXPECT_EQ(report.outcome, MissionReport::Outcome::kEnded) << report;
  EXPECT_LE(report.replans, 3U) << report;
  EXPECT_EQ(report.tasks_done, (std::vector<std::string>{"inspect", "end"})) << report;
}

}  // namespace
}  // namespace sewerplan::executor
