// SPDX-License-Identifier: MIT
#include "sewerplan/domain/plan_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/text_file.h"

#include "support/ais_testbed.h"
#include "support/paths.h"
#include "support/small_map.h"

namespace sewerplan::domain {
namespace {

using ::testing::HasSubstr;
using testing::kCorrectedPaperPlan;
using testing::kPaperPlan;

class PlanTextTest : public ::testing::Test {
 protected:
  void SetUp() override { ais_ = testing::load_ais_testbed(); }

  Result<Plan> parse(std::string_view text) {
    diagnostics_ = Diagnostics{};
    return parse_plan(text, "p.plan", ais_.map, ais_.mission, diagnostics_);
  }

  PipeId pipe(const char* name) const { return *ais_.map.find_pipe(name); }
  ManholeId manhole(const char* name) const { return *ais_.map.find_manhole(name); }

  testing::AisTestbed ais_;
  Diagnostics diagnostics_;
};

TEST_F(PlanTextTest, ReadsThePapersPlanIntoStepsWithIds) {
  Result<Plan> plan = parse(kPaperPlan);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  ASSERT_EQ(plan->steps.size(), 14U);
  EXPECT_EQ(plan->steps[0], PlanStep(DrivePipeToManhole{pipe("P12"), manhole("M2")}));
  EXPECT_EQ(plan->steps[3], PlanStep(DriveManhole{manhole("M3"), SlotIndex{2}, SlotIndex{0}}));
  EXPECT_EQ(plan->steps[6], PlanStep(TakeWaterSample{pipe("P6"), TaskId{0}}));
  EXPECT_EQ(plan->steps[10], PlanStep(InspectPipe{pipe("P4"), TaskId{1}, std::nullopt}));
}

TEST_F(PlanTextTest, WritesThePapersPlanBackLiterally) {
  for (std::string_view text : {kPaperPlan, kCorrectedPaperPlan}) {
    Result<Plan> plan = parse(text);
    ASSERT_TRUE(plan.has_value()) << plan.error();
    EXPECT_EQ(format_plan(*plan, ais_.map, ais_.mission), text);
  }
}

TEST_F(PlanTextTest, TheDatasetsPlanFilesAreThePapersPlanAndItsCorrection) {
  Result<std::string> paper =
      read_text_file(testing::dataset_path("ais-testbed/plans/paper-section-6.plan"));
  Result<std::string> corrected =
      read_text_file(testing::dataset_path("ais-testbed/plans/paper-corrected.plan"));
  ASSERT_TRUE(paper.has_value() && corrected.has_value());
  EXPECT_EQ(*paper, kPaperPlan);
  EXPECT_EQ(*corrected, kCorrectedPaperPlan);
}

TEST_F(PlanTextTest, ReadsFfAndFastDownwardOutputAsTheSamePlan) {
  const std::string ff =
      "step    0: DRIVE_PIPE_TO_MANHOLE P12 M2\n"
      "        1: DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1\n"
      "        2: DRIVE_PIPE_TO_MANHOLE P1 M3\n"
      "        3: DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1 M3 P5 P2 P1\n";
  const std::string fd =
      "(drive_pipe_to_manhole p12 m2)\n"
      "(drive_manhole_type_2_from_1_to_2 m2 p12 p1)\r\n"
      "(drive_pipe_to_manhole p1 m3)\n"
      "(drive_manhole_type_3_type_b_from_3_to_1 m3 p5 p2 p1)\n"
      "; cost = 4 (unit cost)\n";
  const std::string paper(kPaperPlan.substr(0, kPaperPlan.find("DRIVE_PIPE_TO_MANHOLE P5")));
  Result<Plan> expected = parse(paper);
  ASSERT_TRUE(expected.has_value()) << expected.error();
  ASSERT_EQ(expected->steps.size(), 4U);
  Result<Plan> from_ff = parse(ff);
  ASSERT_TRUE(from_ff.has_value()) << from_ff.error();
  EXPECT_EQ(*from_ff, *expected);
  Result<Plan> from_fd = parse(fd);
  ASSERT_TRUE(from_fd.has_value()) << from_fd.error();
  EXPECT_EQ(*from_fd, *expected);
}

TEST_F(PlanTextTest, SkipsBlankAndCommentLinesAndTrailingComments) {
  Result<Plan> plan = parse(
      "\n# the paper's first step\n; another comment\n   \n"
      "  drive_pipe_to_manhole P12 M2   ; 9.4 s\n\tTake_Water_Sample P6\n");
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps.size(), 2U);
  Result<Plan> empty = parse("");
  ASSERT_TRUE(empty.has_value());
  EXPECT_TRUE(empty->steps.empty());
}

TEST_F(PlanTextTest, ReportsEveryBadLineWithItsNumber) {
  Result<Plan> plan = parse(
      "DRIVE_PIPE_TO_MANHOLE P12 M2\n"
      "FLY_TO M3\n"
      "DRIVE_PIPE_TO_MANHOLE P99 M2\n"
      "DRIVE_PIPE_TO_MANHOLE P12\n"
      "DRIVE_MANHOLE_TYPE_3_FROM_3_TO_1 M3 P5 P2 P1\n"
      "DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4 M6 P10 P5 P4 P6\n"
      "DRIVE_MANHOLE_TYPE_2_FROM_1_TO_3 M2 P12 P1\n"
      "DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12\n"
      "TAKE_WATER_SAMPLE P6 nosuchtask\n"
      "TAKE_WATER_SAMPLE P4\n"
      "INSPECT_PIPE P4 M9\n"
      "(drive_pipe_to_manhole p12 m2\n"
      "DRIVE_MANHOLE_TYPE_X M2\n"
      "TAKE_WATER_SAMPLE P6 inspect\n"
      "DRIVE_MANHOLE_TYPE_2_FROM_2_TO_2 M2 P12 P1\n");
  ASSERT_FALSE(plan.has_value());
  EXPECT_EQ(plan.error().code, ErrorCode::kParse);
  const std::string& m = plan.error().message;
  EXPECT_THAT(m, HasSubstr("p.plan:2: error: unknown action 'FLY_TO'"));
  EXPECT_THAT(m, HasSubstr("p.plan:3: error: unknown pipe 'P99'"));
  EXPECT_THAT(m, HasSubstr("p.plan:4: error: DRIVE_PIPE_TO_MANHOLE takes P M, got 1 argument"));
  EXPECT_THAT(m, HasSubstr("p.plan:5: error: M3 is TYPE_3_TYPE_B, not TYPE_3"));
  EXPECT_THAT(m, HasSubstr("p.plan:6: error: M6's pipes in slot order are P10 P4 P5 P6, not "
                           "P10 P5 P4 P6"));
  EXPECT_THAT(m, HasSubstr("p.plan:7: error: slot 3 is out of range: M2 has slots 1 to 2"));
  EXPECT_THAT(m, HasSubstr("p.plan:8: error: DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 takes M2 and its 2 "
                           "pipes in slot order (M2 P12 P1), got 1 pipes"));
  EXPECT_THAT(m, HasSubstr("p.plan:9: error: unknown task 'nosuchtask'"));
  EXPECT_THAT(m, HasSubstr("p.plan:10: error: the mission has no water-sample task in pipe P4"));
  EXPECT_THAT(m, HasSubstr("p.plan:11: error: M9 is not at an end of pipe P4"));
  EXPECT_THAT(m, HasSubstr("p.plan:12: error: a '(' without its ')'"));
  EXPECT_THAT(m, HasSubstr("p.plan:13: error: cannot read 'DRIVE_MANHOLE_TYPE_X'"));
  EXPECT_THAT(m,
              HasSubstr("p.plan:14: error: task 'inspect' is not a water-sample task in pipe P6"));
  EXPECT_THAT(m, HasSubstr("p.plan:15: error: FROM and TO are the same slot 2 of M2"));
  EXPECT_EQ(diagnostics_.error_count(), 14U);
}

TEST_F(PlanTextTest, MatchesNamesIgnoringCaseOnlyWhenThatIsUnambiguous) {
  testing::SmallMap drawing;
  drawing.manhole("M1", 0, 0, true).manhole("m1", 10, 0).pipe("P1", "M1", "m1");
  const SewerMap map = drawing.build();
  const Mission mission = testing::small_mission(map, "P1");
  Diagnostics d;
  Result<Plan> plan = parse_plan("drive_pipe_to_manhole p1 m1\n", "c.plan", map, mission, d);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps[0], PlanStep(DrivePipeToManhole{PipeId{0}, *map.find_manhole("m1")}));
  plan = parse_plan("DRIVE_PIPE_TO_MANHOLE P1 M1\nDRIVE_PIPE_TO_MANHOLE P1 m1\n", "c.plan", map,
                    mission, d);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_NE(plan->steps[0], plan->steps[1]);
  // A name with no exact match that matches several ignoring case is ambiguous.
  testing::SmallMap three;
  three.manhole("Ma", 0, 0, true).manhole("mA", 10, 0).pipe("P1", "Ma", "mA");
  const SewerMap map3 = three.build();
  Diagnostics d3;
  plan = parse_plan("DRIVE_PIPE_TO_MANHOLE P1 MA\n", "c.plan", map3,
                    testing::small_mission(map3, "P1"), d3);
  ASSERT_FALSE(plan.has_value());
  EXPECT_THAT(plan.error().message, HasSubstr("'MA' names several manholes ignoring case: Ma mA"));
}

TEST_F(PlanTextTest, WritesAndRequiresTheTaskNameOnlyWhenTwoTasksAreAlike) {
  testing::SmallMap drawing;
  drawing.manhole("M1", 0, 0, true).manhole("M2", 10, 0).pipe("P1", "M1", "M2");
  const SewerMap map = drawing.build();
  Mission mission = testing::small_mission(map, "M1");
  testing::add_task(mission, map, "left", TaskKind::kTakeWaterSample, "P1", 2.0);
  testing::add_task(mission, map, "right", TaskKind::kTakeWaterSample, "P1", 8.0);
  testing::add_task(mission, map, "visit", TaskKind::kGoTo, "P1", 5.0);
  const PipeId p1 = *map.find_pipe("P1");
  EXPECT_EQ(format_step(TakeWaterSample{p1, TaskId{1}}, map, mission),
            "TAKE_WATER_SAMPLE P1 right");
  EXPECT_EQ(format_step(GoToPoint{p1, TaskId{2}}, map, mission), "GO_TO_POINT P1");
  Diagnostics d;
  Result<Plan> plan = parse_plan("TAKE_WATER_SAMPLE P1\n", "t.plan", map, mission, d);
  ASSERT_FALSE(plan.has_value());
  EXPECT_THAT(plan.error().message,
              HasSubstr("t.plan:1: error: the mission has 2 tasks (left, right) that are a "
                        "water-sample task in pipe P1: name one, as in TAKE_WATER_SAMPLE P1 left"));
  Diagnostics d2;
  plan = parse_plan("TAKE_WATER_SAMPLE P1 RIGHT\nGO_TO_POINT P1\n", "t.plan", map, mission, d2);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps[0], PlanStep(TakeWaterSample{p1, TaskId{1}}));
  EXPECT_EQ(plan->steps[1], PlanStep(GoToPoint{p1, TaskId{2}}));
}

TEST_F(PlanTextTest, WritesAndReadsTheFinishManholeOfAnInspection) {
  const PipeId p4 = pipe("P4");
  const InspectPipe backwards{p4, TaskId{1}, std::uint8_t{0}};
  EXPECT_EQ(format_step(backwards, ais_.map, ais_.mission), "INSPECT_PIPE P4 M6");
  Result<Plan> plan = parse("INSPECT_PIPE P4 M6\ninspect_pipe p4 m5 inspect\n");
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps[0], PlanStep(backwards));
  EXPECT_EQ(plan->steps[1], PlanStep(InspectPipe{p4, TaskId{1}, std::uint8_t{1}}));
  plan = parse("INSPECT_PIPE P4 inspect\n");
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps[0], PlanStep(InspectPipe{p4, TaskId{1}, std::nullopt}));
}

TEST_F(PlanTextTest, WritesABlindFinishEndAsADash) {
  testing::SmallMap drawing;
  drawing.manhole("M1", 0, 0, true).pipe("S1", "M1", "", 0.5, 4.0);
  const SewerMap map = drawing.build();
  Mission mission = testing::small_mission(map, "M1");
  testing::add_task(mission, map, "stub", TaskKind::kInspectPipe, "S1");
  const InspectPipe step{*map.find_pipe("S1"), TaskId{0}, std::uint8_t{1}};
  EXPECT_EQ(format_step(step, map, mission), "INSPECT_PIPE S1 -");
  Diagnostics d;
  Result<Plan> plan =
      parse_plan("ENTER_PIPE M1 S1\nINSPECT_PIPE S1 -\n", "s.plan", map, mission, d);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps[1], PlanStep(step));
  EXPECT_EQ(format_plan(*plan, map, mission), "ENTER_PIPE M1 S1\nINSPECT_PIPE S1 -\n");
}

TEST_F(PlanTextTest, FormatsIdsOutsideTheMapWithoutFailing) {
  const PlanStep step = DrivePipeToManhole{PipeId{99}, ManholeId{7}};
  EXPECT_EQ(format_step(step, ais_.map, ais_.mission), "DRIVE_PIPE_TO_MANHOLE #99 M8");
  EXPECT_EQ(
      format_step(DriveManhole{ManholeId{500}, SlotIndex{0}, SlotIndex{1}}, ais_.map, ais_.mission),
      "DRIVE_MANHOLE_TYPE_?_FROM_1_TO_2 #500");
  EXPECT_EQ(step_kind(step), "drive_pipe_to_manhole");
}

}  // namespace
}  // namespace sewerplan::domain
