// SPDX-License-Identifier: MIT
// Each way a step or a plan can be invalid, and the message that names the objects and the limit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"

#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::domain {
namespace {

using ::testing::HasSubstr;

class ValidatorErrorsTest : public ::testing::Test {
 protected:
  void SetUp() override { ais_ = testing::load_ais_testbed(); }

  // Validates `text` on the AIS map with `mission` (the paper's, possibly changed).
  ValidationReport validate(std::string_view text, const Mission& mission) const {
    Diagnostics diagnostics;
    Result<Plan> plan = parse_plan(text, "e.plan", ais_.map, mission, diagnostics);
    EXPECT_TRUE(plan.has_value()) << plan.error();
    return validate_plan(plan.has_value() ? *plan : Plan{}, ais_.map, mission);
  }
  ValidationReport validate(std::string_view text) const { return validate(text, ais_.mission); }

  // The first n lines of the corrected paper plan.
  static std::string corrected_prefix(std::size_t lines) {
    const std::string_view all = testing::kCorrectedPaperPlan;
    std::size_t end = 0;
    for (std::size_t i = 0; i < lines; ++i) end = all.find('\n', end) + 1;
    return std::string(all.substr(0, end));
  }

  Mission starting_in(const char* pipe) const {
    Mission mission = ais_.mission;
    mission.start = PipeSpot{*ais_.map.find_pipe(pipe), std::nullopt, std::nullopt};
    return mission;
  }

  testing::AisTestbed ais_;
};

TEST_F(ValidatorErrorsTest, ATurnBeyondTheRobotsLimitNamesThePassageAndTheLimit) {
  // M4: P2 leaves at 299.74 deg, P3 at 4.09: from P2 into P3 turns 115.65 degrees.
  const ValidationReport report =
      validate("DRIVE_PIPE_TO_MANHOLE P2 M4\nDRIVE_MANHOLE_TYPE_2_FROM_2_TO_1 M4 P3 P2\n",
               starting_in("P2"));
  EXPECT_EQ(report.failed_step, 1U);
  EXPECT_EQ(report.error,
            "step 2 (DRIVE_MANHOLE_TYPE_2_FROM_2_TO_1 M4 P3 P2): passage M4 slot 2 -> 1 "
            "(P2 -> P3): turn of 115.7 deg exceeds makro-1.1's 90 deg");
}

TEST_F(ValidatorErrorsTest, AStepBeyondTheRobotsLimitNamesThePassageAndTheLimit) {
  // M3: P2's invert is 0.15 m above P1's.
  Mission mission = starting_in("P1");
  mission.profile.max_step_m = 0.1;
  const ValidationReport report =
      validate("DRIVE_PIPE_TO_MANHOLE P1 M3\nDRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_2 M3 P5 P2 P1\n",
               mission);
  EXPECT_EQ(report.failed_step, 1U);
  EXPECT_THAT(report.error, HasSubstr("passage M3 slot 3 -> 2 (P1 -> P2): step of 0.15 m exceeds "
                                      "makro-1.1's 0.10 m"));
}

TEST_F(ValidatorErrorsTest, APipeOutsideTheRobotsDiametersCannotBeEntered) {
  testing::SmallMap drawing;
  drawing.manhole("M1", 0, 0, true).manhole("M2", 10, 0).manhole("M3", 20, 0, true);
  drawing.pipe("P1", "M1", "M2", 0.5).pipe("P20", "M2", "M3", 0.8);
  const SewerMap map = drawing.build();
  const Mission mission = testing::small_mission(map, "P1");
  Diagnostics d;
  Result<Plan> plan =
      parse_plan("DRIVE_PIPE_TO_MANHOLE P1 M2\nDRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P1 P20\n",
                 "d.plan", map, mission, d);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  const ValidationReport report = validate_plan(*plan, map, mission);
  EXPECT_EQ(report.failed_step, 1U);
  EXPECT_THAT(report.error, HasSubstr("pipe P20 is 0.80 m, outside makro-1.1's 0.30-0.60 m"));
}

TEST_F(ValidatorErrorsTest, AStartInAPipeTheRobotCannotDriveFailsAtTheFirstPipeAction) {
  testing::SmallMap drawing;
  drawing.manhole("M1", 0, 0, true).manhole("M2", 10, 0).pipe("P20", "M1", "M2", 0.8);
  const SewerMap map = drawing.build();
  const Mission mission = testing::small_mission(map, "P20");
  const ValidationReport report =
      validate_plan(Plan{{DrivePipeToManhole{PipeId{0}, ManholeId{0}}}}, map, mission);
  EXPECT_EQ(report.error,
            "step 1 (DRIVE_PIPE_TO_MANHOLE P20 M1): the robot starts in pipe P20, which makro-1.1 "
            "cannot drive: pipe P20 is 0.80 m, outside makro-1.1's 0.30-0.60 m");
}

TEST_F(ValidatorErrorsTest, AClosedPipeCannotBeEntered) {
  Mission mission = ais_.mission;
  mission.closed_pipes.push_back(*ais_.map.find_pipe("P1"));
  const ValidationReport report = validate(testing::kCorrectedPaperPlan, mission);
  EXPECT_EQ(report.failed_step, 1U);
  EXPECT_EQ(report.error, "step 2 (DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1): pipe P1 is closed");
}

TEST_F(ValidatorErrorsTest, AClosedPassageIsClosedInBothDirections) {
  Mission mission = ais_.mission;
  // Closed as 1 -> 3; the plan passes 3 -> 1.
  mission.closed_passages.push_back({*ais_.map.find_manhole("M3"), SlotIndex{0}, SlotIndex{2}});
  const ValidationReport report = validate(testing::kCorrectedPaperPlan, mission);
  EXPECT_EQ(report.failed_step, 3U);
  EXPECT_THAT(report.error, HasSubstr("passage M3 slot 3 -> 1 (P1 -> P5) is closed"));
}

TEST_F(ValidatorErrorsTest, TheBatteryLessItsReserveBoundsThePlansEnergy) {
  Mission mission = ais_.mission;
  mission.profile.battery_wh = 20;  // 16 Wh usable = 480 s at 120 W
  ValidationReport report = validate(testing::kCorrectedPaperPlan, mission);
  // After step 11 the plan has taken 471.5 s; step 12 brings it to 518.5 s = 17.28 Wh.
  EXPECT_EQ(report.failed_step, 11U);
  EXPECT_THAT(report.error,
              HasSubstr("battery: 17.28 Wh needed, 16.00 Wh available (makro-1.1's 20 Wh less the "
                        "20% reserve)"));
  // Energy already used at the start counts against the battery too.
  MissionProgress start = initial_progress(ais_.mission, ais_.map);
  start.energy_used_wh = 180;
  Diagnostics d;
  Result<Plan> plan = parse_plan(testing::kCorrectedPaperPlan, "e.plan", ais_.map, ais_.mission, d);
  ASSERT_TRUE(plan.has_value());
  report = validate_plan(*plan, ais_.map, ais_.mission, start);
  EXPECT_THAT(report.error, HasSubstr("12.00 Wh available (makro-1.1's 240 Wh less the 20% "
                                      "reserve and 180.00 Wh used before)"));
}

TEST_F(ValidatorErrorsTest, AnActionInAPipeNeedsTheRobotInThatPipe) {
  const ValidationReport report = validate("TAKE_WATER_SAMPLE P6\n");
  EXPECT_EQ(report.error,
            "step 1 (TAKE_WATER_SAMPLE P6): the robot is in pipe P12 at 2.8285 m, not in pipe P6");
}

TEST_F(ValidatorErrorsTest, ADriveThroughAManholeStartsAtTheSlotTheRobotIsAt) {
  const ValidationReport report =
      validate("DRIVE_PIPE_TO_MANHOLE P12 M2\nDRIVE_MANHOLE_TYPE_2_FROM_2_TO_1 M2 P12 P1\n");
  EXPECT_EQ(report.error,
            "step 2 (DRIVE_MANHOLE_TYPE_2_FROM_2_TO_1 M2 P12 P1): the robot is at M2 slot 1 (P12), "
            "not at M2 slot 2 (P1)");
}

TEST_F(ValidatorErrorsTest, APipeIsLeftOnlyIntoAManholeAtOneOfItsEnds) {
  const ValidationReport report = validate("DRIVE_PIPE_TO_MANHOLE P12 M3\n");
  EXPECT_EQ(report.error, "step 1 (DRIVE_PIPE_TO_MANHOLE P12 M3): M3 is not at an end of pipe P12");
}

TEST_F(ValidatorErrorsTest, ATaskIsDoneOnce) {
  const ValidationReport report = validate(corrected_prefix(7) + "TAKE_WATER_SAMPLE P6\n");
  EXPECT_EQ(report.failed_step, 7U);
  EXPECT_EQ(report.error,
            "step 8 (TAKE_WATER_SAMPLE P6): task 'sample' (take_water_sample) is already done");
}

TEST_F(ValidatorErrorsTest, TheFinalTaskComesAfterEveryOtherAndNothingAfterIt) {
  const std::string to_p9 =
      "DRIVE_MANHOLE_TYPE_4_FROM_4_TO_1 M5 P8 P13 P3 P4\nDRIVE_PIPE_TO_MANHOLE P8 M9\n"
      "DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_1_TO_2 M9 P8 P9 P14\n";
  ValidationReport report = validate(corrected_prefix(14) + "GO_TO_POINT P9\n");
  ASSERT_TRUE(report.valid) << report.error;
  report = validate(corrected_prefix(14) + "GO_TO_POINT P9\nDRIVE_PIPE_TO_MANHOLE P9 M10\n");
  EXPECT_EQ(report.failed_step, 15U);
  EXPECT_EQ(report.error,
            "step 16 (DRIVE_PIPE_TO_MANHOLE P9 M10): step after the final task 'end'");
  // Straight from the start to P9, past M6 and P4 without inspecting: the sample is pending.
  Mission mission = starting_in("P4");
  report = validate("DRIVE_PIPE_TO_MANHOLE P4 M5\n" + to_p9 + "GO_TO_POINT P9\n", mission);
  EXPECT_EQ(report.failed_step, 4U);
  EXPECT_EQ(report.error,
            "step 5 (GO_TO_POINT P9): the final task 'end' must be done last, but task 'sample' "
            "(take_water_sample) is not done");
}

TEST_F(ValidatorErrorsTest, AnUnmetGoalNamesThePendingTask) {
  const ValidationReport report = validate(corrected_prefix(9));
  EXPECT_FALSE(report.valid);
  EXPECT_FALSE(report.failed_step.has_value());
  EXPECT_EQ(report.error, "goal not reached: task 'inspect' (inspect_pipe) is not done");
  EXPECT_EQ(report.step_costs_s.size(), 9U);
}

TEST_F(ValidatorErrorsTest, AnUnmetGoalNamesThePipeOfTheFinalTask) {
  const ValidationReport report = validate(corrected_prefix(13));
  EXPECT_EQ(report.error, "goal not reached: the robot is not in pipe P9 for the final task 'end'");
}

TEST_F(ValidatorErrorsTest, AnUnmetGoalNamesTheExitsWithoutAFinalTask) {
  Mission mission = ais_.mission;
  mission.tasks.pop_back();  // no final task: the mission ends at an exit
  ValidationReport report = validate(corrected_prefix(11), mission);
  EXPECT_EQ(report.error,
            "goal not reached: the robot is not at an exit (exits: M1, M4, M10, M12)");
  report = validate(corrected_prefix(14) + "DRIVE_PIPE_TO_MANHOLE P9 M10\n", mission);
  EXPECT_TRUE(report.valid) << report.error;
}

TEST_F(ValidatorErrorsTest, AnUnmetGoalNamesAFinalTaskAtAPoint) {
  Mission mission = ais_.mission;
  mission.tasks.back().place = PipeSpot{*ais_.map.find_pipe("P9"), 2.0, std::nullopt};
  ValidationReport report = validate(testing::kCorrectedPaperPlan, mission);
  EXPECT_EQ(report.error, "goal not reached: the final task 'end' (go_to) is not done");
  report = validate(std::string(testing::kCorrectedPaperPlan) + "GO_TO_POINT P9\n", mission);
  EXPECT_TRUE(report.valid) << report.error;
  EXPECT_DOUBLE_EQ(report.step_costs_s.back(), 2.0 / 0.3);
}

TEST_F(ValidatorErrorsTest, AnUnmetGoalNamesTheManholeOfAFinalTask) {
  Mission mission = ais_.mission;
  mission.tasks.back().place = *ais_.map.find_manhole("M10");
  ValidationReport report = validate(testing::kCorrectedPaperPlan, mission);
  EXPECT_EQ(report.error,
            "goal not reached: the robot is not at manhole M10 for the final task "
            "'end'");
  report = validate(std::string(testing::kCorrectedPaperPlan) + "DRIVE_PIPE_TO_MANHOLE P9 M10\n",
                    mission);
  EXPECT_TRUE(report.valid) << report.error;
}

TEST_F(ValidatorErrorsTest, ATaskActionMustNameATaskOfItsKindAtItsPlace) {
  const ValidationReport wrong_kind = validate_plan(
      Plan{{TakeWaterSample{*ais_.map.find_pipe("P12"), TaskId{1}}}}, ais_.map, ais_.mission);
  EXPECT_THAT(wrong_kind.error,
              HasSubstr("task 'inspect' is of kind inspect_pipe, not take_water_sample"));
  const ValidationReport wrong_place = validate_plan(
      Plan{{TakeWaterSample{*ais_.map.find_pipe("P12"), TaskId{0}}}}, ais_.map, ais_.mission);
  EXPECT_THAT(wrong_place.error,
              HasSubstr("task 'sample' is at point W1 (pipe P6), not at pipe P12"));
}

}  // namespace
}  // namespace sewerplan::domain
