// SPDX-License-Identifier: MIT
// The validator on the paper's plan and on each action's cost and effect (docs/domain.md).
#include "sewerplan/domain/validator.h"

#include <numeric>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"

#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::domain {
namespace {

using ::testing::HasSubstr;

class ValidatorTest : public ::testing::Test {
 protected:
  void SetUp() override { ais_ = testing::load_ais_testbed(); }

  Plan parse(std::string_view text) const {
    Diagnostics diagnostics;
    Result<Plan> plan = parse_plan(text, "p.plan", ais_.map, ais_.mission, diagnostics);
    EXPECT_TRUE(plan.has_value()) << plan.error();
    return plan.has_value() ? *plan : Plan{};
  }

  testing::AisTestbed ais_;
};

TEST_F(ValidatorTest, ThePapersPlanFailsAtStep11BecauseTheRobotHasLeftP4) {
  const ValidationReport report = validate_plan(parse(testing::kPaperPlan), ais_.map, ais_.mission);
  EXPECT_FALSE(report.valid);
  ASSERT_TRUE(report.failed_step.has_value());
  EXPECT_EQ(*report.failed_step, 10U);
  EXPECT_EQ(report.error,
            "step 11 (INSPECT_PIPE P4): the robot is at M5 slot 4 (P4), not in pipe P4");
  EXPECT_EQ(report.step_costs_s.size(), 10U);
  EXPECT_EQ(report.end.position, RobotPosition(AtSlot{*ais_.map.find_manhole("M5"), SlotIndex{3}}));
}

TEST_F(ValidatorTest, ThePapersPlanWithTheInspectionBeforeTheDriveToM5IsValid) {
  const ValidationReport report =
      validate_plan(parse(testing::kCorrectedPaperPlan), ais_.map, ais_.mission);
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_FALSE(report.failed_step.has_value());
  EXPECT_TRUE(report.error.empty());
  // makro-1.1: v = 0.3 m/s, v_i = 0.1 m/s, 20 s a manhole, 0.3 s a degree of turn, 180 s a
  // sample. The robot starts in the middle of P12 (5.657 m long).
  const double v = 0.3;
  const std::vector<double> expected = {
      (5.657 / 2) / v,    //  1 DRIVE_PIPE_TO_MANHOLE P12 M2: half of P12
      20 + 0 * 0.3,       //  2 M2 1->2: P12 leaves at 225, P1 at 45: straight through
      8.485 / v,          //  3 DRIVE_PIPE_TO_MANHOLE P1 M3: all of P1
      20 + 45 * 0.3,      //  4 M3 3->1: heading in 45 (P1 at 225), out along P5 at 0: 45 deg
      10.0 / v,           //  5 DRIVE_PIPE_TO_MANHOLE P5 M6
      20 + 90 * 0.3,      //  6 M6 3->4: heading in 0 (P5 at 180), out along P6 at 270: 90 deg
      3.0 / v + 180,      //  7 TAKE_WATER_SAMPLE P6: W1 is 3 m into P6, then the sample
      3.0 / v,            //  8 DRIVE_PIPE_TO_MANHOLE P6 M6: back 3 m
      20 + 0 * 0.3,       //  9 M6 4->2: heading in 90 (P6 at 270), out along P4 at 90
      0 / v + 8.0 / 0.1,  // 10 INSPECT_PIPE P4: already at its M6 end; 8 m at 0.1 m/s
      0 / v,              // 11 DRIVE_PIPE_TO_MANHOLE P4 M5: the inspection ended at M5
      20 + 90 * 0.3,      // 12 M5 4->1: heading in 90 (P4 at 270), out along P8 at 0
      10.0 / v,           // 13 DRIVE_PIPE_TO_MANHOLE P8 M9
      20 + 45 * 0.3,      // 14 M9 1->2: heading in 0 (P8 at 180), out along P9 at 315: 45 deg
  };
  ASSERT_EQ(report.step_costs_s.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(report.step_costs_s[i], expected[i], 1e-9) << "step " << i + 1;
  }
  // In all: 37.3135 m at 0.3 m/s, six manholes, 270 degrees of turn, one sample, 8 m inspected.
  const double total = 37.3135 / v + 6 * 20 + 270 * 0.3 + 180 + 80;
  EXPECT_NEAR(report.total_cost_s, total, 1e-9);
  EXPECT_NEAR(report.total_cost_s, 585.3783333333, 1e-9);
  EXPECT_DOUBLE_EQ(report.total_cost_s,
                   std::accumulate(report.step_costs_s.begin(), report.step_costs_s.end(), 0.0));
  EXPECT_NEAR(report.energy_wh, total * 120 / 3600, 1e-9);
  EXPECT_EQ(report.end.position, RobotPosition(InPipe{*ais_.map.find_pipe("P9"), 0.0}));
  EXPECT_EQ(report.end.done, (std::vector<bool>{true, true, false}));
  EXPECT_NEAR(report.end.energy_used_wh, report.energy_wh, 1e-12);
  std::ostringstream out;
  out << report;
  EXPECT_EQ(out.str(), "valid: 14 steps, 585.4 s, 19.5 Wh");
}

TEST_F(ValidatorTest, ReplayStepByStepMatchesTheWholePlan) {
  const Plan plan = parse(testing::kCorrectedPaperPlan);
  PlanReplay replay(ais_.map, ais_.mission, initial_progress(ais_.mission, ais_.map));
  EXPECT_EQ(replay.unmet_goal(), "task 'sample' (take_water_sample) is not done");
  for (const PlanStep& step : plan.steps) ASSERT_TRUE(replay.apply(step).has_value());
  EXPECT_FALSE(replay.unmet_goal().has_value());
  EXPECT_FALSE(replay.finished());  // the final task is a place reached, not an action done
  EXPECT_TRUE(replay.done(TaskId{0}));
  EXPECT_FALSE(replay.done(TaskId{2}));
  EXPECT_DOUBLE_EQ(replay.progress().energy_used_wh, replay.energy_wh());
  EXPECT_DOUBLE_EQ(replay.elapsed_s(), validate_plan(plan, ais_.map, ais_.mission).total_cost_s);
}

TEST_F(ValidatorTest, AFailedStepLeavesTheReplayUnchanged) {
  PlanReplay replay(ais_.map, ais_.mission, initial_progress(ais_.mission, ais_.map));
  const PlanReplay before = replay;
  const Result<double> cost = replay.apply(TakeWaterSample{*ais_.map.find_pipe("P6"), TaskId{0}});
  ASSERT_FALSE(cost.has_value());
  EXPECT_EQ(cost.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(replay.position(), before.position());
  EXPECT_EQ(replay.done(), before.done());
  EXPECT_EQ(replay.elapsed_s(), 0.0);
}

// M1 (exit) -P1 (10 m)- M2 -P2 (20 m)- M3, straight; a blind stub S1 (4 m) off M2.
class SmallValidatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::SmallMap drawing;
    drawing.manhole("M1", 0, 0, true).manhole("M2", 10, 0).manhole("M3", 30, 0);
    drawing.pipe("P1", "M1", "M2").pipe("P2", "M2", "M3").pipe("S1", "M2", "", 0.5, 4.0);
    map_ = drawing.build();
    mission_ = testing::small_mission(map_, "M2");
  }

  ValidationReport validate(std::string_view text) const {
    Diagnostics diagnostics;
    Result<Plan> plan = parse_plan(text, "s.plan", map_, mission_, diagnostics);
    EXPECT_TRUE(plan.has_value()) << plan.error();
    return validate_plan(plan.has_value() ? *plan : Plan{}, map_, mission_);
  }

  SewerMap map_;
  Mission mission_;
};

TEST_F(SmallValidatorTest, EnterPipeFromTheStartManholeCostsOneManholePass) {
  const ValidationReport report = validate("ENTER_PIPE M2 P1\nDRIVE_PIPE_TO_MANHOLE P1 M1\n");
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_EQ(report.step_costs_s, (std::vector<double>{20, 10 / 0.3}));
}

TEST_F(SmallValidatorTest, GoToManholeIsFreeAtAnySlotOrInTheManhole) {
  testing::add_task(mission_, map_, "here", TaskKind::kGoTo, "M2");
  testing::add_task(mission_, map_, "there", TaskKind::kGoTo, "M1");
  const ValidationReport report = validate(
      "GO_TO_MANHOLE M2\nENTER_PIPE M2 P1\nDRIVE_PIPE_TO_MANHOLE P1 M1\nGO_TO_MANHOLE M1\n");
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_EQ(report.step_costs_s[0], 0.0);
  EXPECT_EQ(report.step_costs_s[3], 0.0);
}

TEST_F(SmallValidatorTest, AWholePipeTaskIsDoneWhereTheRobotIs) {
  testing::add_task(mission_, map_, "anywhere", TaskKind::kTakeWaterSample, "P1");
  testing::add_task(mission_, map_, "at7", TaskKind::kGoTo, "P1", 7.0);
  const ValidationReport report = validate(
      "ENTER_PIPE M2 P1\nTAKE_WATER_SAMPLE P1\nGO_TO_POINT P1\nDRIVE_PIPE_TO_MANHOLE P1 M1\n");
  ASSERT_TRUE(report.valid) << report.error;
  // P1 runs from M1 (offset 0) to M2 (offset 10): entered at 10, sampled there, then to 7.
  EXPECT_EQ(report.step_costs_s, (std::vector<double>{20, 180, 3 / 0.3, 7 / 0.3}));
}

TEST_F(SmallValidatorTest, InspectionFromInsideAPipeDrivesToItsStartEndFirst) {
  mission_.start = PipeSpot{*map_.find_pipe("P2"), 5.0, std::nullopt};
  testing::add_task(mission_, map_, "inspect", TaskKind::kInspectPipe, "P2");
  // P2 runs from M2 (0) to M3 (20); finishing at M3 starts at M2: 5 m back, then 20 m scanning.
  ValidationReport report = validate(
      "INSPECT_PIPE P2 M3\nDRIVE_PIPE_TO_MANHOLE P2 M2\nDRIVE_MANHOLE_TYPE_3_FROM_2_TO_1 "
      "M2 P1 P2 S1\nDRIVE_PIPE_TO_MANHOLE P1 M1\n");
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_DOUBLE_EQ(report.step_costs_s[0], 5 / 0.3 + 20 / 0.1);
  EXPECT_DOUBLE_EQ(report.step_costs_s[1], 20 / 0.3);
  report = validate("INSPECT_PIPE P2\n");
  EXPECT_EQ(report.error,
            "step 1 (INSPECT_PIPE P2): the robot is in pipe P2 at 5 m, not at an end: "
            "INSPECT_PIPE P2 must name the manhole where the inspection finishes");
}

TEST_F(SmallValidatorTest, InspectingABlindPipeEndsAtItsBlindEnd) {
  testing::add_task(mission_, map_, "stub", TaskKind::kInspectPipe, "S1");
  const ValidationReport report = validate(
      "ENTER_PIPE M2 S1\nINSPECT_PIPE S1 -\nDRIVE_PIPE_TO_MANHOLE S1 M2\n"
      "DRIVE_MANHOLE_TYPE_3_FROM_3_TO_1 M2 P1 P2 S1\nDRIVE_PIPE_TO_MANHOLE P1 M1\n");
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_DOUBLE_EQ(report.step_costs_s[1], 4 / 0.1);
  EXPECT_DOUBLE_EQ(report.step_costs_s[2], 4 / 0.3);
}

TEST_F(SmallValidatorTest, StepsWithIdsOutsideTheMapAreErrorsNotCrashes) {
  const std::vector<PlanStep> steps = {DrivePipeToManhole{PipeId{50}, ManholeId{0}},
                                       DriveManhole{ManholeId{50}, SlotIndex{0}, SlotIndex{1}},
                                       EnterPipe{ManholeId{1}, PipeId{50}},
                                       TakeWaterSample{PipeId{0}, TaskId{9}},
                                       InspectPipe{PipeId{9}, TaskId{0}, std::uint8_t{7}},
                                       GoToManhole{ManholeId{1}, TaskId{3}},
                                       DriveManhole{ManholeId{1}, SlotIndex{0}, SlotIndex{9}}};
  for (const PlanStep& step : steps) {
    const ValidationReport report = validate_plan(Plan{{step}}, map_, mission_);
    EXPECT_FALSE(report.valid);
    EXPECT_EQ(report.failed_step, 0U) << report.error;
  }
}

TEST_F(SmallValidatorTest, AWrongStartIsReportedNotApplied) {
  MissionProgress start = initial_progress(mission_, map_);
  start.position = InPipe{*map_.find_pipe("P1"), 11.0};
  ValidationReport report = validate_plan(Plan{}, map_, mission_, start);
  EXPECT_EQ(report.error, "invalid start: offset 11 m is outside pipe P1 (0 to 10 m)");
  start = initial_progress(mission_, map_);
  start.done.push_back(true);
  report = validate_plan(Plan{}, map_, mission_, start);
  EXPECT_EQ(report.error, "invalid start: the start has 1 task flags for 0 tasks");
}

}  // namespace
}  // namespace sewerplan::domain
