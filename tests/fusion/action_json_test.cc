// SPDX-License-Identifier: MIT
// Robot actions as JSON lines for the event log: names, not IDs; slots and steps from 1.
#include "sewerplan/fusion/action_json.h"

#include <gtest/gtest.h>

#include "fusion/fusion_testing.h"
#include "support/ais_testbed.h"

namespace sewerplan::fusion {
namespace {

class ActionJsonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ais_ = sewerplan::testing::load_ais_testbed();
    Result<FusedPlan> fused =
        testing::fuse_text(sewerplan::testing::kCorrectedPaperPlan, ais_.map, ais_.mission);
    ASSERT_TRUE(fused.has_value()) << fused.error();
    fused_ = *fused;
  }

  std::string json(std::size_t index) const {
    return write_action_json(fused_.actions.at(index), ais_.map, ais_.mission);
  }

  sewerplan::testing::AisTestbed ais_;
  FusedPlan fused_;
};

TEST_F(ActionJsonTest, APassageNamesItsManholeAndPipesWithPaperSlotNumbers) {
  EXPECT_EQ(json(5),
            R"({"kind":"pass_manhole","plan_step":6,"manhole":"M6","from_slot":3,"to_slot":4,)"
            R"("from_pipe":"P5","to_pipe":"P6","turn_deg":90.0,"step_m":0.0,)"
            R"("manhole_diameter_m":1.5,"duration_s":47.0})");
}

TEST_F(ActionJsonTest, ADriveBackToAManholeHasItsDirectionAndTypeVariant) {
  EXPECT_EQ(json(7),
            R"({"kind":"drive_to_manhole","plan_step":8,"pipe":"P6","manhole":"M6",)"
            R"("direction":"backward","distance_m":3.0,"manhole_type":4,"manhole_variant":null,)"
            R"("pipe_diameter_m":0.6,"speed_mps":0.3,"from_offset_m":3.0,"to_offset_m":0.0,)"
            R"("duration_s":10.0})");
  EXPECT_NE(json(2).find(R"("manhole":"M3","direction":"forward")"), std::string::npos);
  EXPECT_NE(json(2).find(R"("manhole_variant":"B")"), std::string::npos);
}

TEST_F(ActionJsonTest, TheSampleAndTheInspectionNameTheirTasks) {
  EXPECT_EQ(json(6),
            R"({"kind":"take_water_sample","plan_step":7,"pipe":"P6","offset_m":3.0,)"
            R"("task":"sample","drive":{"direction":"forward","distance_m":3.0,"speed_mps":0.3},)"
            R"("sample_s":180.0,"duration_s":190.0})");
  EXPECT_EQ(
      json(9),
      R"({"kind":"inspect_pipe","plan_step":10,"pipe":"P4","task":"inspect","length_m":8.0,)"
      R"("speed_mps":0.1,"start_manhole":"M6","finish_manhole":"M5","scan_direction":"forward",)"
      R"("approach":{"direction":"forward","distance_m":0.0,"speed_mps":0.3},)"
      R"("duration_s":80.0})");
}

}  // namespace
}  // namespace sewerplan::fusion
