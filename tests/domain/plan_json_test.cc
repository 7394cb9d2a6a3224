// SPDX-License-Identifier: MIT
#include "sewerplan/domain/plan_json.h"

#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sewerplan/domain/plan_text.h"

#include "support/ais_testbed.h"

namespace sewerplan::domain {
namespace {

nlohmann::json plan_json(std::string_view text, const testing::AisTestbed& ais) {
  Diagnostics diagnostics;
  Result<Plan> plan = parse_plan(text, "p.plan", ais.map, ais.mission, diagnostics);
  EXPECT_TRUE(plan.has_value()) << plan.error();
  if (!plan.has_value()) return {};
  std::ostringstream out;
  write_plan_json(*plan, validate_plan(*plan, ais.map, ais.mission), ais.map, ais.mission, out);
  return nlohmann::json::parse(out.str());
}

TEST(PlanJson, WritesEachStepsTextKindObjectsAndCost) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  const nlohmann::json j = plan_json(testing::kCorrectedPaperPlan, ais);
  EXPECT_EQ(j["format"], "sewerplan-plan");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["valid"], true);
  EXPECT_FALSE(j.contains("error"));
  EXPECT_NEAR(j["cost_s"].get<double>(), 585.3783333333, 1e-9);
  EXPECT_NEAR(j["energy_wh"].get<double>(), 585.3783333333 / 30, 1e-9);
  ASSERT_EQ(j["steps"].size(), 14U);
  const nlohmann::json& first = j["steps"][0];
  EXPECT_EQ(first["action"], "DRIVE_PIPE_TO_MANHOLE P12 M2");
  EXPECT_EQ(first["kind"], "drive_pipe_to_manhole");
  EXPECT_EQ(first["pipe"], "P12");
  EXPECT_EQ(first["manhole"], "M2");
  const nlohmann::json& turn = j["steps"][3];
  EXPECT_EQ(turn["kind"], "drive_manhole");
  EXPECT_EQ(turn["manhole"], "M3");
  EXPECT_EQ(turn["from_slot"], 3);
  EXPECT_EQ(turn["to_slot"], 1);
  EXPECT_EQ(turn["from_pipe"], "P1");
  EXPECT_EQ(turn["to_pipe"], "P5");
  EXPECT_DOUBLE_EQ(turn["cost_s"].get<double>(), 33.5);
  const nlohmann::json& sample = j["steps"][6];
  EXPECT_EQ(sample["kind"], "take_water_sample");
  EXPECT_EQ(sample["task"], "sample");
  EXPECT_EQ(sample["pipe"], "P6");
}

TEST(PlanJson, AnInvalidPlanSaysWhereAndWhy) {
  const testing::AisTestbed ais = testing::load_ais_testbed();
  const nlohmann::json j = plan_json(testing::kPaperPlan, ais);
  EXPECT_EQ(j["valid"], false);
  EXPECT_EQ(j["failed_step"], 11);
  EXPECT_EQ(j["error"],
            "step 11 (INSPECT_PIPE P4): the robot is at M5 slot 4 (P4), not in pipe P4");
  EXPECT_TRUE(j["steps"][9].contains("cost_s"));
  EXPECT_FALSE(j["steps"][10].contains("cost_s"));
  EXPECT_EQ(j["steps"][10]["task"], "inspect");
}

}  // namespace
}  // namespace sewerplan::domain
