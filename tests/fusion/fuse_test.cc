// SPDX-License-Identifier: MIT
// Plan fusion on the paper's plan and on small maps: every parameter from the map and the
// profile, directions from the robot's heading, durations equal to the validator's costs, and the
// errors for bad steps and bad data.
#include "sewerplan/fusion/fuse.h"

#include <sstream>
#include <variant>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/map_queries.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/fusion/action_text.h"

#include "fusion/fusion_testing.h"
#include "support/ais_testbed.h"
#include "support/small_map.h"

namespace sewerplan::fusion {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

using testing::fuse_text;
using testing::parse;

template <class T>
const T& action_at(const FusedPlan& plan, std::size_t index) {
  EXPECT_LT(index, plan.actions.size());
  const T* action = std::get_if<T>(&plan.actions.at(index));
  EXPECT_NE(action, nullptr) << "action " << index << " is " << plan.actions.at(index);
  return *action;
}

class FusePaperPlanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ais_ = sewerplan::testing::load_ais_testbed();
    plan_ = parse(sewerplan::testing::kCorrectedPaperPlan, ais_.map, ais_.mission);
    Result<FusedPlan> fused =
        fuse(plan_, ais_.map, ais_.mission, domain::initial_progress(ais_.mission, ais_.map));
    ASSERT_TRUE(fused.has_value()) << fused.error();
    fused_ = *fused;
  }

  ManholeId manhole(std::string_view name) const { return *ais_.map.find_manhole(name); }
  PipeId pipe(std::string_view name) const { return *ais_.map.find_pipe(name); }

  sewerplan::testing::AisTestbed ais_;
  domain::Plan plan_;
  FusedPlan fused_;
};

TEST_F(FusePaperPlanTest, GivesOneActionPerStepWithItsStepIndex) {
  ASSERT_EQ(fused_.actions.size(), plan_.steps.size());
  for (std::size_t i = 0; i < fused_.actions.size(); ++i) {
    EXPECT_EQ(plan_step(fused_.actions[i]), i);
  }
  EXPECT_EQ(action_kind(fused_.actions[0]), "drive_to_manhole");
  EXPECT_EQ(action_kind(fused_.actions[1]), "pass_manhole");
  EXPECT_EQ(action_kind(fused_.actions[6]), "take_water_sample");
  EXPECT_EQ(action_kind(fused_.actions[9]), "inspect_pipe");
}

TEST_F(FusePaperPlanTest, DurationsSumToTheValidatorsTotalCost) {
  const domain::ValidationReport report = domain::validate_plan(plan_, ais_.map, ais_.mission);
  ASSERT_TRUE(report.valid) << report.error;
  ASSERT_EQ(report.step_costs_s.size(), fused_.actions.size());
  for (std::size_t i = 0; i < fused_.actions.size(); ++i) {
    EXPECT_EQ(duration_s(fused_.actions[i]), report.step_costs_s[i]) << "step " << i + 1;
  }
  EXPECT_EQ(fused_.total_duration_s(), report.total_cost_s);
  EXPECT_NEAR(fused_.total_duration_s(), 585.4, 0.05);
}

TEST_F(FusePaperPlanTest, TheDriveInP12GoesForwardFromTheStartOffsetToM2) {
  const auto& drive = action_at<DriveToManhole>(fused_, 0);
  const Pipe& p12 = ais_.map.pipe(pipe("P12"));
  const double start_offset = p12.length_m / 2;  // a start in a pipe: its middle
  EXPECT_EQ(drive.pipe, pipe("P12"));
  EXPECT_EQ(drive.manhole, manhole("M2"));
  EXPECT_EQ(drive.direction, Direction::kForward);  // the start faces ends[1], which is M2
  EXPECT_DOUBLE_EQ(drive.distance_m, start_offset);
  EXPECT_DOUBLE_EQ(drive.from_offset_m, start_offset);
  EXPECT_DOUBLE_EQ(drive.to_offset_m, p12.length_m);
  EXPECT_EQ(drive.manhole_type, 2);
  EXPECT_FALSE(drive.manhole_variant.has_value());
  EXPECT_EQ(drive.pipe_diameter_m, 0.6);
  EXPECT_EQ(drive.speed_mps, ais_.mission.profile.speed_mps);
  EXPECT_DOUBLE_EQ(drive.duration_s, start_offset / 0.3);
}

TEST_F(FusePaperPlanTest, ThePassageOfM6FromSlot3To4HasTheMapsTurnAndStep) {
  const auto& pass = action_at<PassManhole>(fused_, 5);
  const ManholeId m6 = manhole("M6");
  EXPECT_EQ(pass.manhole, m6);
  EXPECT_EQ(pass.from_slot, SlotIndex{2});
  EXPECT_EQ(pass.to_slot, SlotIndex{3});
  EXPECT_EQ(pass.from_pipe, pipe("P5"));
  EXPECT_EQ(pass.to_pipe, pipe("P6"));
  EXPECT_EQ(pass.turn_deg, passage_turn_deg(ais_.map, m6, SlotIndex{2}, SlotIndex{3}));
  EXPECT_EQ(pass.step_m, passage_step_m(ais_.map, m6, SlotIndex{2}, SlotIndex{3}));
  EXPECT_DOUBLE_EQ(pass.turn_deg, 90);
  EXPECT_EQ(pass.manhole_diameter_m, 1.5);
  const RobotProfile& profile = ais_.mission.profile;
  EXPECT_DOUBLE_EQ(pass.duration_s, profile.manhole_pass_s + 90 * profile.turn_s_per_deg);
}

TEST_F(FusePaperPlanTest, TheTypeBManholeKeepsItsVariant) {
  const auto& drive = action_at<DriveToManhole>(fused_, 2);  // DRIVE_PIPE_TO_MANHOLE P1 M3
  EXPECT_EQ(drive.manhole_type, 3);
  EXPECT_EQ(drive.manhole_variant, 'B');
}

TEST_F(FusePaperPlanTest, TheSampleIsTakenAtW1AndTheRobotBacksOutToM6) {
  const auto& sample = action_at<TakeWaterSample>(fused_, 6);
  EXPECT_EQ(sample.pipe, pipe("P6"));
  EXPECT_DOUBLE_EQ(sample.offset_m, ais_.map.point(*ais_.map.find_point("W1")).offset_m);
  EXPECT_EQ(sample.drive.direction, Direction::kForward);
  EXPECT_DOUBLE_EQ(sample.drive.distance_m, 3.0);
  EXPECT_EQ(sample.sample_s, ais_.mission.profile.sample_s);
  // P6 was entered from M6, so driving back to M6 is against the heading.
  const auto& back = action_at<DriveToManhole>(fused_, 7);
  EXPECT_EQ(back.manhole, manhole("M6"));
  EXPECT_EQ(back.direction, Direction::kBackward);
  EXPECT_DOUBLE_EQ(back.distance_m, 3.0);
}

TEST_F(FusePaperPlanTest, TheInspectionOfP4ScansItsLengthFromM6WithoutApproach) {
  const auto& inspect = action_at<InspectPipe>(fused_, 9);
  EXPECT_EQ(inspect.pipe, pipe("P4"));
  EXPECT_EQ(inspect.length_m, 8.0);
  EXPECT_EQ(inspect.speed_mps, ais_.mission.profile.inspection_speed_mps);
  EXPECT_EQ(inspect.start_end, 0);   // M6
  EXPECT_EQ(inspect.finish_end, 1);  // M5
  EXPECT_EQ(inspect.approach.distance_m, 0);
  EXPECT_EQ(inspect.scan_direction, Direction::kForward);
  // Then the robot is already at M5's end: a drive of 0 m.
  const auto& drive = action_at<DriveToManhole>(fused_, 10);
  EXPECT_EQ(drive.distance_m, 0);
  EXPECT_EQ(drive.direction, Direction::kForward);
}

TEST_F(FusePaperPlanTest, PrintsEachActionWithItsStep) {
  std::ostringstream out;
  out << fused_;
  EXPECT_THAT(out.str(), HasSubstr("step 1: DriveToManhole(pipe #11 -> manhole #1, forward 2.83 m "
                                   "at 0.30 m/s, type 2, pipe 0.60 m) [9.4 s]"));
  EXPECT_THAT(out.str(), HasSubstr("step 6: PassManhole(manhole #5, slot 3 -> 4, turn 90.0 deg"));
}

// Logs name the objects as the map and the mission do, never by their internal indices (issue 18).
TEST_F(FusePaperPlanTest, DescribesAnActionByTheNamesOfItsObjects) {
  EXPECT_EQ(describe(fused_.actions.at(0), ais_.map, ais_.mission),
            "DriveToManhole(pipe P12 -> manhole M2, forward 2.83 m at 0.30 m/s, type 2, pipe "
            "0.60 m) [9.4 s]");
  EXPECT_THAT(describe(fused_.actions.at(5), ais_.map, ais_.mission),
              HasSubstr("PassManhole(manhole M6, slot 3 -> 4"));
  const std::string sample = describe(fused_.actions.at(6), ais_.map, ais_.mission);
  EXPECT_THAT(sample, HasSubstr("TakeWaterSample(pipe P6 at 3.00 m, task sample,"));
  EXPECT_THAT(sample, Not(HasSubstr("#")));
}

TEST_F(FusePaperPlanTest, AnInvalidStepIsAnErrorNamingTheStep) {
  const domain::Plan plan = parse(
      "DRIVE_PIPE_TO_MANHOLE P12 M2\n"
      "DRIVE_PIPE_TO_MANHOLE P1 M3\n",
      ais_.map, ais_.mission);
  Result<FusedPlan> fused =
      fuse(plan, ais_.map, ais_.mission, domain::initial_progress(ais_.mission, ais_.map));
  ASSERT_FALSE(fused.has_value());
  EXPECT_EQ(fused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(
      fused.error().message,
      "step 2 (DRIVE_PIPE_TO_MANHOLE P1 M3): the robot is at M2 slot 1 (P12), not in pipe P1");
}

TEST_F(FusePaperPlanTest, AnInvalidStartIsAnError) {
  domain::MissionProgress start = domain::initial_progress(ais_.mission, ais_.map);
  start.done.pop_back();
  Result<FusedPlan> fused = fuse(plan_, ais_.map, ais_.mission, start);
  ASSERT_FALSE(fused.has_value());
  EXPECT_EQ(fused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(fused.error().message, HasSubstr("invalid start: "));
}

TEST_F(FusePaperPlanTest, AnInvalidProfileIsAnError) {
  Mission mission = ais_.mission;
  mission.profile.speed_mps = 0;
  Result<FusedPlan> fused =
      fuse(plan_, ais_.map, mission, domain::initial_progress(mission, ais_.map));
  ASSERT_FALSE(fused.has_value());
  EXPECT_EQ(fused.error().code, ErrorCode::kInvalidProfile);
}

TEST_F(FusePaperPlanTest, AnEmptyPlanFusesToNoActions) {
  Result<FusedPlan> fused = fuse(domain::Plan{}, ais_.map, ais_.mission,
                                 domain::initial_progress(ais_.mission, ais_.map));
  ASSERT_TRUE(fused.has_value()) << fused.error();
  EXPECT_TRUE(fused->actions.empty());
  EXPECT_EQ(fused->total_duration_s(), 0);
}

// M1 -- P1 (10 m) -- M2 -- P2 (10 m, 90 deg turn, 0.1 m up at M2) -- M3.
class FuseSmallMapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    map_ = sewerplan::testing::SmallMap()
               .manhole("M1", 0, 0, /*exit=*/true)
               .manhole("M2", 10, 0)
               .manhole("M3", 10, 10, /*exit=*/true)
               .pipe("P1", "M1", "M2")
               .pipe("P2", "M2", "M3")
               .invert("M2", "P2", 0.1)
               .build();
  }

  SewerMap map_;
};

TEST_F(FuseSmallMapTest, EnterGoToPointPassAndGoToManholeFromAManholeStart) {
  Mission mission = sewerplan::testing::small_mission(map_, "M1");
  sewerplan::testing::add_task(mission, map_, "point", TaskKind::kGoTo, "P1", 4.0);
  sewerplan::testing::add_task(mission, map_, "end", TaskKind::kGoTo, "M3", std::nullopt,
                               /*final=*/true);
  Result<FusedPlan> fused = fuse_text(
      "ENTER_PIPE M1 P1\n"
      "GO_TO_POINT P1\n"
      "DRIVE_PIPE_TO_MANHOLE P1 M2\n"
      "DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P1 P2\n"
      "DRIVE_PIPE_TO_MANHOLE P2 M3\n"
      "GO_TO_MANHOLE M3\n",
      map_, mission);
  ASSERT_TRUE(fused.has_value()) << fused.error();
  const RobotProfile& profile = mission.profile;

  const auto& enter = action_at<EnterPipe>(*fused, 0);
  EXPECT_EQ(enter.slot, SlotIndex{0});
  EXPECT_EQ(enter.pipe, *map_.find_pipe("P1"));
  EXPECT_EQ(enter.duration_s, profile.manhole_pass_s);

  const auto& point = action_at<GoToPoint>(*fused, 1);
  EXPECT_EQ(point.offset_m, 4.0);
  EXPECT_EQ(point.drive, (PipeDrive{Direction::kForward, 4.0, profile.speed_mps}));

  const auto& drive = action_at<DriveToManhole>(*fused, 2);
  EXPECT_EQ(drive.direction, Direction::kForward);
  EXPECT_DOUBLE_EQ(drive.distance_m, 6.0);

  const auto& pass = action_at<PassManhole>(*fused, 3);
  EXPECT_DOUBLE_EQ(pass.turn_deg, 90);
  EXPECT_DOUBLE_EQ(pass.step_m, 0.1);
  EXPECT_DOUBLE_EQ(pass.duration_s, profile.manhole_pass_s + 90 * profile.turn_s_per_deg +
                                        0.1 * profile.step_s_per_m);
  EXPECT_EQ(pass.manhole_diameter_m, 1.0);

  const auto& go = action_at<GoToManhole>(*fused, 5);
  EXPECT_EQ(go.manhole, *map_.find_manhole("M3"));
  EXPECT_EQ(go.duration_s, 0);

  const domain::ValidationReport report =
      domain::validate_plan(parse("ENTER_PIPE M1 P1\nGO_TO_POINT P1\nDRIVE_PIPE_TO_MANHOLE P1 "
                                  "M2\nDRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P1 P2\n"
                                  "DRIVE_PIPE_TO_MANHOLE P2 M3\nGO_TO_MANHOLE M3\n",
                                  map_, mission),
                            map_, mission);
  ASSERT_TRUE(report.valid) << report.error;
  EXPECT_EQ(fused->total_duration_s(), report.total_cost_s);
}

TEST_F(FuseSmallMapTest, ASampleMidPipeThenBackOutTheWayItCameDrivesBackward) {
  Mission mission = sewerplan::testing::small_mission(map_, "M1");
  sewerplan::testing::add_task(mission, map_, "sample", TaskKind::kTakeWaterSample, "P1", 7.5);
  Result<FusedPlan> fused = fuse_text(
      "ENTER_PIPE M1 P1\nTAKE_WATER_SAMPLE P1\nDRIVE_PIPE_TO_MANHOLE P1 M1\n", map_, mission);
  ASSERT_TRUE(fused.has_value()) << fused.error();
  const auto& sample = action_at<TakeWaterSample>(*fused, 1);
  EXPECT_EQ(sample.offset_m, 7.5);
  EXPECT_EQ(sample.drive.direction, Direction::kForward);
  EXPECT_EQ(sample.drive.distance_m, 7.5);
  const auto& back = action_at<DriveToManhole>(*fused, 2);
  EXPECT_EQ(back.direction, Direction::kBackward);
  EXPECT_EQ(back.distance_m, 7.5);
  EXPECT_EQ(back.from_offset_m, 7.5);
  EXPECT_EQ(back.to_offset_m, 0);
}

TEST_F(FuseSmallMapTest, AStartInAPipeFacesEnds1UnlessTheOptionsSayOtherwise) {
  const Mission mission = sewerplan::testing::small_mission(map_, "P1");  // its middle, 5 m
  const std::string_view plan = "DRIVE_PIPE_TO_MANHOLE P1 M1\n";
  Result<FusedPlan> by_convention = fuse_text(plan, map_, mission);
  ASSERT_TRUE(by_convention.has_value()) << by_convention.error();
  EXPECT_EQ(action_at<DriveToManhole>(*by_convention, 0).direction, Direction::kBackward);

  Result<FusedPlan> facing_m1 = fuse_text(plan, map_, mission, {.start_heading_end = 0});
  ASSERT_TRUE(facing_m1.has_value()) << facing_m1.error();
  EXPECT_EQ(action_at<DriveToManhole>(*facing_m1, 0).direction, Direction::kForward);

  Result<FusedPlan> bad = fuse_text(plan, map_, mission, {.start_heading_end = 2});
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
}

TEST_F(FuseSmallMapTest, AnInspectionFromTheMiddleApproachesItsStartEndBackward) {
  Mission mission = sewerplan::testing::small_mission(map_, "M1");
  sewerplan::testing::add_task(mission, map_, "sample", TaskKind::kTakeWaterSample, "P1", 3.0);
  sewerplan::testing::add_task(mission, map_, "inspect", TaskKind::kInspectPipe, "P1");
  Result<FusedPlan> fused =
      fuse_text("ENTER_PIPE M1 P1\nTAKE_WATER_SAMPLE P1\nINSPECT_PIPE P1 M2\n", map_, mission);
  ASSERT_TRUE(fused.has_value()) << fused.error();
  const auto& inspect = action_at<InspectPipe>(*fused, 2);
  EXPECT_EQ(inspect.start_end, 0);
  EXPECT_EQ(inspect.finish_end, 1);
  EXPECT_EQ(inspect.approach, (PipeDrive{Direction::kBackward, 3.0, mission.profile.speed_mps}));
  EXPECT_DOUBLE_EQ(inspect.duration_s,
                   3.0 / mission.profile.speed_mps + 10.0 / mission.profile.inspection_speed_mps);
}

TEST_F(FuseSmallMapTest, AnInspectionFinishingAtTheEntryEndScansBackward) {
  Mission mission = sewerplan::testing::small_mission(map_, "M1");
  sewerplan::testing::add_task(mission, map_, "sample", TaskKind::kTakeWaterSample, "P1", 3.0);
  sewerplan::testing::add_task(mission, map_, "inspect", TaskKind::kInspectPipe, "P1");
  Result<FusedPlan> fused =
      fuse_text("ENTER_PIPE M1 P1\nTAKE_WATER_SAMPLE P1\nINSPECT_PIPE P1 M1\n", map_, mission);
  ASSERT_TRUE(fused.has_value()) << fused.error();
  const auto& inspect = action_at<InspectPipe>(*fused, 2);
  EXPECT_EQ(inspect.start_end, 1);
  EXPECT_EQ(inspect.finish_end, 0);
  EXPECT_EQ(inspect.approach, (PipeDrive{Direction::kForward, 7.0, mission.profile.speed_mps}));
  EXPECT_EQ(inspect.scan_direction, Direction::kBackward);
}

// A manhole recorded narrower than the pipes that open into it: the diameter is wrong, and a turn
// planned in it would be too.
SewerMap narrow_manhole_map() {
  MapBuilder builder("narrow");
  builder.add_manhole({.name = "M1",
                       .position = {0, 0, 0},
                       .diameter_m = 1.0,
                       .exit = true,
                       .slots = {{.pipe = "P1", .azimuth_deg = 0}}});
  builder.add_manhole(
      {.name = "M2",
       .position = {10, 0, 0},
       .diameter_m = 0.4,
       .slots = {{.pipe = "P1", .azimuth_deg = 180}, {.pipe = "P2", .azimuth_deg = 0}}});
  builder.add_manhole({.name = "M3",
                       .position = {20, 0, 0},
                       .diameter_m = 1.0,
                       .exit = true,
                       .slots = {{.pipe = "P2", .azimuth_deg = 180}}});
  builder.add_pipe({.name = "P1", .from = "M1", .to = "M2", .length_m = 10, .diameter_m = 0.5});
  builder.add_pipe({.name = "P2", .from = "M2", .to = "M3", .length_m = 10, .diameter_m = 0.5});
  Diagnostics diagnostics;
  Result<SewerMap> map = std::move(builder).build(diagnostics);
  EXPECT_TRUE(map.has_value()) << map.error();
  return map.has_value() ? std::move(map).value() : SewerMap{};
}

TEST(FuseBadDataTest, AManholeNarrowerThanItsPipesIsAnInvalidMapErrorNamingIt) {
  const SewerMap map = narrow_manhole_map();
  const Mission mission = sewerplan::testing::small_mission(map, "P1");
  Result<FusedPlan> fused = fuse_text(
      "DRIVE_PIPE_TO_MANHOLE P1 M2\nDRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P1 P2\n", map, mission);
  ASSERT_FALSE(fused.has_value());
  EXPECT_EQ(fused.error().code, ErrorCode::kInvalidMap);
  EXPECT_EQ(fused.error().message,
            "step 2 (DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P1 P2): manhole M2 (0.40 m) is narrower "
            "than pipe P1 (0.50 m) that opens into it: its diameter cannot be right");
}

TEST(FuseBadDataTest, EnteringFromANarrowManholeIsAnInvalidMapError) {
  const SewerMap map = narrow_manhole_map();
  const Mission mission = sewerplan::testing::small_mission(map, "M2");
  Result<FusedPlan> fused = fuse_text("ENTER_PIPE M2 P2\n", map, mission);
  ASSERT_FALSE(fused.has_value());
  EXPECT_EQ(fused.error().code, ErrorCode::kInvalidMap);
  EXPECT_THAT(fused.error().message, HasSubstr("manhole M2 (0.40 m) is narrower than pipe P2"));
}

}  // namespace
}  // namespace sewerplan::fusion
