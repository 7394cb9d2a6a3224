// SPDX-License-Identifier: MIT
// The OMPL module (sewerplan/modules/ompl_table.h) as `motion precompute` gets it: its planner,
// injected into fusion, plans what the motion library's planner, linked, plans.
#include <gtest/gtest.h>

#include "sewerplan/core/robot_profile.h"
#include "sewerplan/fusion/manhole_turn_planner.h"
#include "sewerplan/modules/ompl.h"
#if SEWERPLAN_TEST_WITH_OMPL
#include "sewerplan/motion/ompl_head_path_planner.h"
#endif

namespace sewerplan::modules {
namespace {

TEST(OmplModuleTest, ItsPlannerPlansWhatTheLinkedOnePlans) {
  const Result<const fusion::HeadPathPlanner*> loaded = ompl_head_path_planner();
#if SEWERPLAN_TEST_WITH_OMPL
  ASSERT_TRUE(loaded.has_value()) << loaded.error();
  ASSERT_NE(*loaded, nullptr);
  EXPECT_EQ(*ompl_head_path_planner(), *loaded);  // loaded once
  const RobotProfile profile = *builtin_profile("makro-1.1");
  const fusion::PassageGeometry right_angle{
      .manhole_diameter_m = 1.0, .turn_deg = 90, .from_diameter_m = 0.6, .to_diameter_m = 0.6};
  Result<fusion::TurnPlan> through_module =
      fusion::ManholeTurnPlanner(*loaded, fusion::robot_body(profile), profile).plan(right_angle);
  const motion::OmplHeadPathPlanner linked;
  Result<fusion::TurnPlan> direct =
      fusion::ManholeTurnPlanner(&linked, fusion::robot_body(profile), profile).plan(right_angle);
  ASSERT_TRUE(through_module.has_value()) << through_module.error();
  ASSERT_TRUE(direct.has_value()) << direct.error();
  EXPECT_TRUE(through_module->feasible) << through_module->reason;
  EXPECT_EQ(*through_module, *direct);
#else
  ASSERT_FALSE(loaded.has_value());
  EXPECT_EQ(loaded.error().code, ErrorCode::kUnsupportedFormat);
  EXPECT_NE(loaded.error().message.find("no OMPL"), std::string::npos);
#endif
}

}  // namespace
}  // namespace sewerplan::modules
