// SPDX-License-Identifier: MIT
// The staged recovery table (recovery.h): one row per manoeuvre, in the order the stages are
// tried, and the "recovery" events carry the table's stages.
#include "sewerplan/executor/recovery.h"

#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

TEST(RecoveryTable, EveryManoeuvreHasOneRowAndANameOfItsOwn) {
  std::set<RecoveryPhase> phases;
  std::set<std::string_view> names;
  for (const RecoveryStage& stage : kRecoveryTable) {
    phases.insert(stage.phase);
    names.insert(stage.logged);
    EXPECT_FALSE(stage.tries.empty());
    EXPECT_FALSE(stage.gives_up.empty());
  }
  EXPECT_EQ(phases.size(), kRecoveryTable.size());
  EXPECT_EQ(names.size(), kRecoveryTable.size());
  EXPECT_EQ(logged_name(RecoveryPhase::kBackUpAndRetry), "1: back up and retry");
}

TEST(RecoveryTable, TheBlockageStagesAreTriedInTheTablesOrder) {
  // A permanent obstacle with push allowed goes through every blockage stage.
  const auto ais = testing::load_ais_testbed();
  Diagnostics d;
  auto faults = hal::read_faults_json(R"({"format": "sewerplan-faults", "version": 1,
      "obstacles": [{"pipe": "P1", "offset_m": 3.0, "kind": "permanent"}]})",
                                      "test.json", ais.map, d);
  ASSERT_TRUE(faults.has_value()) << d.error_summary();
  ManualClock clock;
  Replanner replanner(ais.map, ais.mission, {.clock = &clock});
  const auto& start = std::get<domain::InPipe>(replanner.progress().position);
  hal::SimRobot robot(ais.map, ais.mission.profile,
                      hal::InPipe{start.pipe, start.offset_m, hal::Heading::kTowardsEnd1}, *faults);
  ExecutorOptions options;
  options.recovery.push_allowed = true;
  Executor executor(ais.map, replanner, robot, options);
  std::vector<RecoveryPhase> tried;
  executor.subscribe([&](const Event& e) {
    const auto* recovery = std::get_if<RecoveryEvent>(&e.what);
    if (recovery != nullptr && (tried.empty() || tried.back() != recovery->phase)) {
      tried.push_back(recovery->phase);
    }
  });
  static_cast<void>(executor.run());
  std::vector<RecoveryPhase> expected;
  for (const RecoveryStage& stage : kRecoveryTable) {
    if (stage.error == hal::RobotErrorKind::kBlockage) expected.push_back(stage.phase);
  }
  ASSERT_GE(tried.size(), expected.size());
  EXPECT_EQ(std::vector<RecoveryPhase>(tried.begin(), tried.begin() + 3), expected);
}

TEST(RecoverySettings, ReadsEveryFieldAndKeepsTheDefaultsOfTheRest) {
  Result<RecoveryConfig> c = read_recovery_json(
      R"({"backup_retries": 3, "backup_m": 0.1, "push_allowed": true, "max_reboots": 0})",
      "r.json");
  ASSERT_TRUE(c.has_value()) << c.error();
  EXPECT_EQ(c->backup_retries, 3);
  EXPECT_DOUBLE_EQ(c->backup_m, 0.1);
  EXPECT_TRUE(c->push_allowed);
  EXPECT_EQ(c->max_reboots, 0);
  EXPECT_EQ(c->lift_retries, RecoveryConfig{}.lift_retries);
}

TEST(RecoverySettings, NamesEveryBadFieldByJsonPath) {
  Result<RecoveryConfig> c = read_recovery_json(
      R"({"backup_retries": 2.5, "backup_m": 11, "lift_retries": -1, "push_allowed": "yes",
          "max_reboot": 2, "max_reboots": 1, "max_reboots": 3})",
      "r.json");
  ASSERT_FALSE(c.has_value());
  const std::string& e = c.error().message;
  for (const char* expected :
       {"r.json:$.backup_retries: error: expected a whole number from 0 to 1000, got 2.5",
        "r.json:$.backup_m: error: expected metres from 0 to 10, got 11",
        "r.json:$.lift_retries: error: expected a whole number from 0 to 1000, got -1",
        "r.json:$.push_allowed: error: expected true or false, got \"yes\"",
        "r.json:$.max_reboot: error: unknown field 'max_reboot'",
        "r.json:$.max_reboots: error: field 'max_reboots' given twice"}) {
    EXPECT_NE(e.find(expected), std::string::npos) << expected << "\n" << e;
  }
  Result<RecoveryConfig> syntax = read_recovery_json("{\"backup_m\": }", "r.json");
  ASSERT_FALSE(syntax.has_value());
  EXPECT_NE(syntax.error().message.find("r.json:1:"), std::string::npos) << syntax.error();
}

}  // namespace
}  // namespace sewerplan::executor
