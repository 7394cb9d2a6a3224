// SPDX-License-Identifier: MIT
// PDDL export (what the files say) and import of FF's and Fast Downward's plans.
#include "sewerplan/domain/pddl.h"

#include <gtest/gtest.h>

#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"

#include "support/ais_testbed.h"
#include "support/pddl_sim.h"
#include "support/small_map.h"

namespace sewerplan::domain {
namespace {

using testing::AisTestbed;
using testing::load_ais_testbed;
using testing::PddlSim;
using testing::SmallMap;

bool contains(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

TEST(PddlExport, WritesThePapersVocabularyAndTheMissionsFacts) {
  const AisTestbed ais = load_ais_testbed();
  auto files = export_pddl(ais.map, ais.mission);
  ASSERT_TRUE(files.has_value()) << files.error();
  EXPECT_TRUE(contains(files->domain, "(:requirements :strips :typing)"));
  EXPECT_TRUE(contains(files->domain, "(:action DRIVE_PIPE_TO_MANHOLE"));
  EXPECT_TRUE(contains(files->domain, "(:action DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1"));
  EXPECT_TRUE(contains(files->domain, "(:action DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4"));
  EXPECT_TRUE(contains(files->domain, "(:action TAKE_WATER_SAMPLE"));
  EXPECT_TRUE(contains(files->domain, "(:action INSPECT_PIPE"));
  EXPECT_FALSE(contains(files->domain, "total-cost")) << "FF 2.3 reads no action costs";
  // The paper's mission starts in P12 and ends in P9 (a final go-to of a whole pipe): that is a
  // goal, with no bookkeeping action.
  EXPECT_TRUE(contains(files->problem, "(in-pipe P12)"));
  EXPECT_TRUE(contains(files->problem, "(:goal (and (sampled P6) (inspected P4) (in-pipe P9)))"));
  EXPECT_FALSE(contains(files->domain, "(:action REACH_EXIT"));
  EXPECT_FALSE(contains(files->domain, "(:action ALL_OTHER_TASKS_DONE"));
  // What PDDL cannot carry is said in both files.
  EXPECT_TRUE(contains(files->domain, "battery"));
  EXPECT_TRUE(contains(files->problem, "battery"));
}

TEST(PddlExport, ActionCostsAreTheProfilesInMilliseconds) {
  const AisTestbed ais = load_ais_testbed();
  auto files = export_pddl(ais.map, ais.mission, {.action_costs = true});
  ASSERT_TRUE(files.has_value()) << files.error();
  EXPECT_TRUE(contains(files->domain, ":action-costs"));
  EXPECT_TRUE(contains(files->problem, "(:metric minimize (total-cost))"));
  // ENTER_PIPE costs manhole_pass_s; sampling sample_s (makro-1.1: 20 s and 180 s).
  EXPECT_TRUE(contains(files->domain, "(increase (total-cost) 20000)"));
  EXPECT_TRUE(contains(files->domain, "(increase (total-cost) 180000)"));
  const Pipe& p6 = ais.map.pipe(*ais.map.find_pipe("P6"));
  EXPECT_TRUE(contains(files->problem,
                       "(= (drive-cost P6) " + std::to_string(to_cost(p6.length_m / 0.30)) + ")"));
}

// Plans the paper's corrected plan through the PDDL semantics: the export lets exactly the route
// the native domain allows, and the goal holds at its end.
TEST(PddlExport, ThePapersCorrectedPlanSolvesTheExport) {
  const AisTestbed ais = load_ais_testbed();
  auto files = export_pddl(ais.map, ais.mission);
  ASSERT_TRUE(files.has_value());
  PddlSim sim(files->domain, files->problem);
  const std::vector<std::vector<std::string>> steps = {
      {"DRIVE_PIPE_TO_MANHOLE", "P12", "M2"},
      {"DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2", "M2", "P12", "P1"},
      {"DRIVE_PIPE_TO_MANHOLE", "P1", "M3"},
      {"DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1", "M3", "P5", "P2", "P1"},
      {"DRIVE_PIPE_TO_MANHOLE", "P5", "M6"},
      {"DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4", "M6", "P10", "P4", "P5", "P6"},
      {"TAKE_WATER_SAMPLE", "P6"},
      {"DRIVE_PIPE_TO_MANHOLE", "P6", "M6"},
      {"DRIVE_MANHOLE_TYPE_4_FROM_4_TO_2", "M6", "P10", "P4", "P5", "P6"},
      {"INSPECT_PIPE", "P4", "M5"},
      {"DRIVE_PIPE_TO_MANHOLE", "P4", "M5"},
      {"DRIVE_MANHOLE_TYPE_4_FROM_4_TO_1", "M5", "P8", "P13", "P3", "P4"},
      {"DRIVE_PIPE_TO_MANHOLE", "P8", "M9"}};
  for (const auto& step : steps) {
    ASSERT_EQ(sim.apply(step.front(), {step.begin() + 1, step.end()}), std::nullopt) << step[0];
  }
  EXPECT_FALSE(sim.goal_reached());
  ASSERT_EQ(sim.apply("DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_1_TO_2", {"M9", "P8", "P9", "P14"}),
            std::nullopt);
  EXPECT_TRUE(sim.goal_reached());
}

// The robot's limits are static facts: a passage beyond the turn limit and a closed pipe are not
// there, so no planner can use them.
TEST(PddlExport, LimitsAndClosuresAreCompiledIn) {
  const SewerMap map = SmallMap()
                           .manhole("A", 0, 0, true)
                           .manhole("B", 10, 0)
                           .manhole("C", 10, 10)  // 90 degrees at B: allowed
                           .manhole("D", 0, -1)   // a sharp turn at B: not allowed
                           .manhole("E", 20, 0)
                           .pipe("P1", "A", "B")
                           .pipe("P2", "B", "C")
                           .pipe("P3", "B", "D")
                           .pipe("P4", "B", "E")
                           .build();
  Mission mission = testing::small_mission(map, "A");
  mission.closed_pipes.push_back(*map.find_pipe("P4"));
  auto files = export_pddl(map, mission);
  ASSERT_TRUE(files.has_value());
  EXPECT_TRUE(contains(files->problem, "(passage B P1 P2)"));
  EXPECT_FALSE(contains(files->problem, "(passage B P1 P3)"));
  EXPECT_FALSE(contains(files->problem, "(passage B P1 P4)")) << "P4 is closed";
  EXPECT_FALSE(contains(files->problem, "(can-enter B P4)"));
  EXPECT_TRUE(contains(files->problem, "(can-enter B P2)"));
}

TEST(PddlNames, KeepsPddlNamesAndRenamesTheRestReversibly) {
  const SewerMap map = SmallMap()
                           .manhole("M1", 0, 0, true)
                           .manhole("1002", 10, 0)      // starts with a digit
                           .manhole("and", 20, 0)       // a PDDL keyword
                           .pipe("m1", "M1", "1002")    // the manhole's name, ignoring case
                           .pipe("P.2", "1002", "and")  // a character PDDL does not allow
                           .build();
  const Mission mission = testing::small_mission(map, "M1");
  const PddlNames names(map, mission);
  EXPECT_EQ(names.manhole(*map.find_manhole("M1")), "M1");
  EXPECT_EQ(names.manhole(*map.find_manhole("1002")), "m-1002");
  EXPECT_EQ(names.manhole(*map.find_manhole("and")), "m-and");
  EXPECT_EQ(names.pipe(*map.find_pipe("m1")), "p-m1");
  EXPECT_EQ(names.pipe(*map.find_pipe("P.2")), "p-P_2");
  EXPECT_EQ(names.renamed_count(), 4U);
  EXPECT_EQ(names.original("M-1002"), "1002");  // FF writes names in upper case
  EXPECT_EQ(names.original("p-p_2"), "P.2");    // Fast Downward in lower case
  EXPECT_EQ(names.original("m1"), "M1");
  EXPECT_EQ(names.original("P99"), std::nullopt);
}

// --- import ------------------------------------------------------------------------------------

// FF's output around its plan, as FF 2.3 prints it.
constexpr std::string_view kFfOutput =
    "\nff: parsing domain file\ndomain 'SEWER' defined\n ... done.\nff: parsing problem file\n"
    "problem 'MISSION' defined\n ... done.\n\n\n"
    "Cueing down from goal distance:   10 into depth [1]\n                                  9  "
    "[1]\n"
    "\nff: found legal plan as follows\n\n"
    "step    0: DRIVE_PIPE_TO_MANHOLE P12 M2\n"
    "        1: DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1\n"
    "        2: DRIVE_PIPE_TO_MANHOLE P1 M3\n"
    "        3: DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_3_TO_1 M3 P5 P2 P1\n"
    "        4: DRIVE_PIPE_TO_MANHOLE P5 M6\n"
    "        5: DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4 M6 P10 P4 P5 P6\n"
    "        6: TAKE_WATER_SAMPLE P6\n"
    "        7: DRIVE_PIPE_TO_MANHOLE P6 M6\n"
    "        8: DRIVE_MANHOLE_TYPE_4_FROM_4_TO_2 M6 P10 P4 P5 P6\n"
    "        9: INSPECT_PIPE P4 M5\n"
    "       10: DRIVE_PIPE_TO_MANHOLE P4 M5\n"
    "       11: DRIVE_MANHOLE_TYPE_4_FROM_4_TO_1 M5 P8 P13 P3 P4\n"
    "       12: DRIVE_PIPE_TO_MANHOLE P8 M9\n"
    "       13: DRIVE_MANHOLE_TYPE_3_TYPE_B_FROM_1_TO_2 M9 P8 P9 P14\n"
    "     \n\ntime spent:    0.00 seconds instantiating 180 easy, 0 hard action templates\n"
    "               0.00 seconds total time\n\n";

TEST(PddlImport, ReadsFfsOutputAsThePapersPlan) {
  const AisTestbed ais = load_ais_testbed();
  Diagnostics diagnostics;
  auto plan =
      import_pddl_plan(kFfOutput, "ff.out", PddlPlanFormat::kFf, ais.map, ais.mission, diagnostics);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(plan->steps.size(), 14U);
  const ValidationReport report = validate_plan(*plan, ais.map, ais.mission);
  EXPECT_TRUE(report.valid) << report.error;
  EXPECT_NEAR(report.total_cost_s, 585.4, 0.05);
}

TEST(PddlImport, ReadsFastDownwardsSasPlanAndDropsBookkeeping) {
  const SewerMap map = SmallMap()
                           .manhole("M1", 0, 0, true)
                           .manhole("1002", 10, 0)
                           .manhole("M3", 20, 0, true)
                           .pipe("P1", "M1", "1002")
                           .pipe("P2", "1002", "M3")
                           .build();
  Mission mission = testing::small_mission(map, "M1");
  mission.tasks.push_back(
      {.name = "s", .kind = TaskKind::kTakeWaterSample, .place = PipeSpot{*map.find_pipe("P2")}});
  const std::string sas_plan =
      "(enter_pipe m1 p1)\n(drive_pipe_to_manhole p1 m-1002)\n"
      "(drive_manhole_type_2_from_1_to_2 m-1002 p1 p2)\n(take_water_sample p2)\n"
      "(drive_pipe_to_manhole p2 m3)\n(reach_exit m3)\n; cost = 6 (unit cost)\n";
  Diagnostics diagnostics;
  auto plan = import_pddl_plan(sas_plan, "sas_plan", PddlPlanFormat::kFastDownward, map, mission,
                               diagnostics);
  ASSERT_TRUE(plan.has_value()) << plan.error();
  EXPECT_EQ(format_plan(*plan, map, mission),
            "ENTER_PIPE M1 P1\nDRIVE_PIPE_TO_MANHOLE P1 1002\n"
            "DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 1002 P1 P2\nTAKE_WATER_SAMPLE P2\n"
            "DRIVE_PIPE_TO_MANHOLE P2 M3\n");
  EXPECT_TRUE(validate_plan(*plan, map, mission).valid);
}

TEST(PddlImport, UnknownNamesAndStrayLinesAreErrorsWithTheirLine) {
  const AisTestbed ais = load_ais_testbed();
  Diagnostics diagnostics;
  auto plan = import_pddl_plan(
      "(drive_pipe_to_manhole p12 m2)\n(drive_pipe_to_manhole p99 m2)\n"
      "drive_manhole p1\n(fly_to m2)\n",
      "sas_plan", PddlPlanFormat::kFastDownward, ais.map, ais.mission, diagnostics);
  ASSERT_FALSE(plan.has_value());
  EXPECT_EQ(plan.error().code, ErrorCode::kParse);
  const std::string summary = diagnostics.error_summary();
  EXPECT_TRUE(contains(summary, "sas_plan:2")) << summary;
  EXPECT_TRUE(contains(summary, "'p99'")) << summary;
  EXPECT_TRUE(contains(summary, "sas_plan:3")) << summary;
  EXPECT_TRUE(contains(summary, "parentheses")) << summary;
  EXPECT_FALSE(contains(summary, "sas_plan:1:")) << summary;
}

TEST(PddlImport, UnknownActionIsAnErrorWithItsLine) {
  const AisTestbed ais = load_ais_testbed();
  Diagnostics diagnostics;
  auto plan = import_pddl_plan("(fly_to m2)\n", "sas_plan", PddlPlanFormat::kFastDownward, ais.map,
                               ais.mission, diagnostics);
  ASSERT_FALSE(plan.has_value());
  EXPECT_TRUE(contains(diagnostics.error_summary(), "sas_plan:1")) << diagnostics.error_summary();
  EXPECT_TRUE(contains(diagnostics.error_summary(), "FLY_TO")) << diagnostics.error_summary();
}

TEST(PddlImport, FfsNoPlanVerdictIsTheError) {
  const AisTestbed ais = load_ais_testbed();
  Diagnostics diagnostics;
  auto plan = import_pddl_plan(
      "ff: parsing domain file\n\nbest first search space empty! problem proven unsolvable.\n",
      "ff.out", PddlPlanFormat::kFf, ais.map, ais.mission, diagnostics);
  ASSERT_FALSE(plan.has_value());
  EXPECT_TRUE(contains(diagnostics.error_summary(), "ff.out:3")) << diagnostics.error_summary();
  EXPECT_TRUE(contains(diagnostics.error_summary(), "FF found no plan"));
}

// Issue 16: an empty or cut-off FF output was read as an empty plan ("goal not reached").
TEST(PddlImport, EmptyOrCrashedFfOutputHoldsNoPlanIssue16) {
  const AisTestbed ais = load_ais_testbed();
  for (const char* text : {"", "ff: parsing domain file\nSegmentation fault\n"}) {
    Diagnostics diagnostics;
    auto plan =
        import_pddl_plan(text, "ff.out", PddlPlanFormat::kFf, ais.map, ais.mission, diagnostics);
    ASSERT_FALSE(plan.has_value()) << text;
    EXPECT_TRUE(contains(diagnostics.error_summary(), "holds no FF plan"))
        << diagnostics.error_summary();
  }
}

}  // namespace
}  // namespace sewerplan::domain
