// SPDX-License-Identifier: MIT
// The staged recovery table (recovery.h): one row per manoeuvre, in the order the stages are
// tried, and the "recovery" events carry the table's stages.
#include "sewerplan/executor/recovery.h"

#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sewerplan/core/text_file.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "support/ais_testbed.h"
#include "support/paths.h"

namespace sewerplan::executor {
namespace {

TEST(RecoveryTable, EveryManoeuvreHasOneRowAndNamesOfItsOwn) {
  std::set<RecoveryPhase> phases;
  std::set<std::string_view> names;
  std::set<std::string_view> logged;
  for (const RecoveryManoeuvre& m : kRecoveryManoeuvres) {
    phases.insert(m.phase);
    names.insert(m.name);
    logged.insert(m.logged);
    EXPECT_FALSE(m.gives_up.empty());
    EXPECT_EQ(&manoeuvre(m.phase), &m);
  }
  EXPECT_EQ(phases.size(), kRecoveryManoeuvres.size());
  EXPECT_EQ(names.size(), kRecoveryManoeuvres.size());
  EXPECT_EQ(logged.size(), kRecoveryManoeuvres.size());
  EXPECT_EQ(logged_name(RecoveryPhase::kBackUpAndRetry), "1: back up and retry");
  // The default table has each manoeuvre once, within its bound.
  std::set<RecoveryPhase> rows;
  for (const RecoveryStage& stage : kRecoveryTable) {
    EXPECT_TRUE(rows.insert(stage.phase).second);
    EXPECT_LE(stage.tries, manoeuvre(stage.phase).max_tries);
    EXPECT_EQ(stage.distance_m > 0, manoeuvre(stage.phase).drives);
  }
  EXPECT_EQ(rows.size(), kRecoveryManoeuvres.size());
}

// The paper's mission on the AIS test bed under `profile`, with a permanent obstacle in P1 (no
// row clears it, so every blockage row is tried), its events to `observer`.
void run_into_permanent_obstacle(const RecoveryProfile& profile, const EventObserver& observer) {
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
  options.recovery = profile;
  Executor executor(ais.map, replanner, robot, options);
  executor.subscribe(observer);
  static_cast<void>(executor.run());
}

// The recovery phases logged, each run of one phase once.
std::vector<RecoveryPhase> phases_tried(const RecoveryProfile& profile) {
  std::vector<RecoveryPhase> tried;
  run_into_permanent_obstacle(profile, [&](const Event& e) {
    const auto* recovery = std::get_if<RecoveryEvent>(&e.what);
    if (recovery != nullptr && (tried.empty() || tried.back() != recovery->phase)) {
      tried.push_back(recovery->phase);
    }
  });
  return tried;
}

RecoveryProfile rows(std::vector<RecoveryStage> stages) {
  RecoveryProfile profile;
  profile.stages = std::move(stages);
  profile.push_allowed = true;
  return profile;
}

TEST(RecoveryTable, TheBlockageStagesAreTriedInTheTablesOrder) {
  RecoveryProfile profile;
  profile.push_allowed = true;
  const std::vector<RecoveryPhase> tried = phases_tried(profile);
  std::vector<RecoveryPhase> expected;
  for (const RecoveryStage& stage : kRecoveryTable) {
    if (manoeuvre(stage.phase).error == hal::RobotErrorKind::kBlockage) {
      expected.push_back(stage.phase);
    }
  }
  ASSERT_GE(tried.size(), expected.size());
  EXPECT_EQ(std::vector<RecoveryPhase>(tried.begin(), tried.begin() + 3), expected);
}

// The profile is the running policy: its rows, in its order, as often as their bounds say; a row
// left out is not tried. (Before issue 33 the stages were fixed in the code, whatever the table.)
TEST(RecoveryTable, TheProfilesRowsAreTheRunningPolicy) {
  using P = RecoveryPhase;
  EXPECT_EQ(
      phases_tried(rows({{P::kLiftHeadAndRetry, 1}, {P::kPush, 1}, {P::kBackUpAndRetry, 1, 0.05}})),
      (std::vector<P>{P::kLiftHeadAndRetry, P::kPush, P::kBackUpAndRetry}));
  EXPECT_EQ(phases_tried(rows({{P::kPush, 1}, {P::kLiftHeadAndRetry, 0}})),
            (std::vector<P>{P::kPush}));
  EXPECT_EQ(phases_tried(rows({})), (std::vector<P>{}));
}

TEST(RecoveryTable, ARowsBoundCountsItsTries) {
  using P = RecoveryPhase;
  std::size_t lifts = 0;
  std::size_t blockages = 0;
  run_into_permanent_obstacle(rows({{P::kLiftHeadAndRetry, 3}}), [&](const Event& e) {
    if (const auto* r = std::get_if<RecoveryEvent>(&e.what)) {
      lifts += r->phase == P::kLiftHeadAndRetry ? 1 : 0;
    }
    if (const auto* f = std::get_if<FailureEvent>(&e.what)) {
      blockages += f->kind == Failure::Kind::kBlockage ? 1 : 0;
    }
  });
  ASSERT_GT(blockages, 0U);
  EXPECT_EQ(lifts, 3 * blockages);
}

TEST(RecoveryProfileFile, TheDefaultFileIsTheBuiltInTable) {
  const std::string file = testing::dataset_path("recovery/default.json").string();
  Result<std::string> text = read_text_file(file);
  ASSERT_TRUE(text.has_value()) << text.error();
  Result<RecoveryProfile> p = read_recovery_json(*text, file);
  ASSERT_TRUE(p.has_value()) << p.error();
  EXPECT_EQ(*p, RecoveryProfile{});
}

TEST(RecoveryProfileFile, AListReplacesThatErrorsRowsInItsOrder) {
  Result<RecoveryProfile> p = read_recovery_json(
      R"({"format": "sewerplan-recovery", "version": 1, "push_allowed": true,
          "blockage": [{"manoeuvre": "push", "tries": 3},
                       {"manoeuvre": "back-up", "tries": 1, "distance_m": 0.1}],
          "danger": []})",
      "r.json");
  ASSERT_TRUE(p.has_value()) << p.error();
  using P = RecoveryPhase;
  EXPECT_EQ(p->stages, (std::vector<RecoveryStage>{
                           {P::kReboot, 2}, {P::kPush, 3}, {P::kBackUpAndRetry, 1, 0.1}}));
  EXPECT_TRUE(p->push_allowed);
  EXPECT_EQ(p->tries(P::kLiftHeadAndRetry), 0);
  EXPECT_EQ(p->tries(P::kPush), 3);
  RecoveryProfile no_push = *p;
  no_push.push_allowed = false;
  EXPECT_EQ(no_push.tries(P::kPush), 0);
}

TEST(RecoveryProfileFile, NamesEveryBadFieldByJsonPath) {
  Result<RecoveryProfile> p = read_recovery_json(
      R"({"format": "sewerplan-recovery", "version": 2, "max_reboots": 2,
          "malfunction": [{"manoeuvre": "reboot", "tries": -1}],
          "blockage": [{"manoeuvre": "back-up", "tries": 2.5, "distance_m": 11},
                       {"manoeuvre": "reboot"}, {"manoeuvre": "lift-head", "distance_m": 1},
                       {"manoeuvre": "lift-head"}, {"manoeuvre": "back-up"}, "push"],
          "danger": [{"manoeuvre": "back-off", "tries": 2, "distance_m": 0.3, "tries": 1}],
          "push_allowed": "yes"})",
      "r.json");
  ASSERT_FALSE(p.has_value());
  const std::string& e = p.error().message;
  for (const char* expected :
       {"r.json:$.version: error: expected 1, got 2",
        "r.json:$.max_reboots: error: unknown field 'max_reboots'",
        "r.json:$.malfunction[0].tries: error: expected a whole number from 0 to 1000, got -1",
        "r.json:$.blockage[0].tries: error: expected a whole number from 0 to 1000, got 2.5",
        "r.json:$.blockage[0].distance_m: error: expected metres from 0 to 10, got 11",
        "r.json:$.blockage[1].manoeuvre: error: expected a manoeuvre for a blockage "
        "(\"back-up\", \"lift-head\", \"push\"), got \"reboot\"",
        "r.json:$.blockage[2].distance_m: error: \"lift-head\" drives no distance",
        "r.json:$.blockage[3].manoeuvre: error: \"lift-head\" given twice",
        "r.json:$.blockage[4]: error: missing required field 'distance_m'",
        "r.json:$.blockage[5]: error: expected an object, got \"push\"",
        "r.json:$.danger[0].tries: error: field 'tries' given twice",
        "r.json:$.push_allowed: error: expected true or false, got \"yes\""}) {
    EXPECT_NE(e.find(expected), std::string::npos) << expected << "\n" << e;
  }
  Result<RecoveryProfile> two = read_recovery_json(
      R"({"format": "sewerplan-recovery", "version": 1,
          "danger": [{"manoeuvre": "back-off", "tries": 2, "distance_m": 0.3}]})",
      "r.json");
  ASSERT_FALSE(two.has_value());
  EXPECT_NE(two.error().message.find(
                "r.json:$.danger[0].tries: error: expected a whole number from 0 to 1, got 2"),
            std::string::npos)
      << two.error();
  Result<RecoveryProfile> syntax = read_recovery_json("{\"danger\": }", "r.json");
  ASSERT_FALSE(syntax.has_value());
  EXPECT_NE(syntax.error().message.find("r.json:1:"), std::string::npos) << syntax.error();
  Result<RecoveryProfile> no_format = read_recovery_json("{}", "r.json");
  ASSERT_FALSE(no_format.has_value());
  EXPECT_NE(no_format.error().message.find("r.json:$: error: missing required field 'format'"),
            std::string::npos)
      << no_format.error();
}

}  // namespace
}  // namespace sewerplan::executor
