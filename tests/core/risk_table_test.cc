// SPDX-License-Identifier: MIT
// Risk table files (--risk-table, docs/formats/risk-table.md): the shipped default is the built-in
// table, a table round-trips, and every mistake names the file and its JSON path.
#include <algorithm>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/generator.h"
#include "sewerplan/core/robot_profile.h"

#include "support/paths.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;

TEST(RiskTableJson, TheShippedDefaultIsTheBuiltInTable) {
  Diagnostics d;
  Result<RiskTable> table =
      read_risk_table(testing::dataset_path("condition/default-risk-table.json"), d);
  ASSERT_TRUE(table.has_value()) << table.error();
  EXPECT_EQ(*table, default_risk_table());
  EXPECT_EQ(d.warning_count(), 0U);
}

TEST(RiskTableJson, RoundTrips) {
  RiskTable table = default_risk_table();
  table.rules.push_back({.code = "BD",
                         .characterisation = "A",
                         .effect = RiskEffect::kBlockage,
                         .probability = 0.25,
                         .meaning = "other"});
  std::ostringstream out;
  write_risk_table_json(table, out);
  Diagnostics d;
  Result<RiskTable> back = read_risk_table_json(out.str(), "t.json", d);
  ASSERT_TRUE(back.has_value()) << back.error();
  EXPECT_EQ(*back, table);
}

TEST(RiskTableJson, ErrorsNameTheFileAndPath) {
  const std::string text = R"({"format": "sewerplan-risk-table", "version": 1, "rules": [
    {"code": "BAC", "effect": "impassable"},
    {"code": "BBA", "effect": "blocked"},
    {"code": "BBC", "effect": "blockage", "probability": 1.5},
    {"code": "", "effect": "none", "colour": "red"}]})";
  Diagnostics d;
  Result<RiskTable> table = read_risk_table_json(text, "t.json", d);
  ASSERT_FALSE(table.has_value());
  EXPECT_THAT(table.error().message, HasSubstr("t.json:$.rules[1].effect: error: unknown effect"));
  EXPECT_THAT(table.error().message, HasSubstr("t.json:$.rules[2].probability"));
  EXPECT_THAT(table.error().message, HasSubstr("t.json:$.rules[3].code"));
  EXPECT_EQ(d.warning_count(), 1U);  // the unknown "colour"
}

TEST(RiskTableJson, BlockageFindingsBecomeHazards) {
  GeneratorOptions options{.manholes = 60, .seed = 3, .findings_per_km = 200};
  Result<SewerMap> map = generate_network(options);
  ASSERT_TRUE(map.has_value()) << map.error();
  ASSERT_GT(map->finding_count(), 0U);
  const std::vector<FindingRisk> risks =
      assess_findings(*map, *builtin_profile("makro-1.1"), default_risk_table());
  const std::vector<Hazard> hazards = blockage_hazards(*map, risks);
  std::size_t blockages = 0;
  for (const FindingRisk& r : risks) blockages += r.effect == RiskEffect::kBlockage ? 1 : 0;
  EXPECT_EQ(hazards.size(), blockages);
  for (const Hazard& h : hazards) {
    EXPECT_GT(h.probability, 0);
    EXPECT_LE(h.probability, 1);
    EXPECT_LE(h.offset_m, map->pipe(h.pipe).length_m);
  }
}

TEST(GeneratorFindings, SameNetworkWithOrWithoutFindingsAndDeterministic) {
  GeneratorOptions options{.manholes = 80, .seed = 5};
  Result<SewerMap> plain = generate_network(options);
  options.findings_per_km = 50;
  Result<SewerMap> with = generate_network(options);
  Result<SewerMap> again = generate_network(options);
  ASSERT_TRUE(plain.has_value() && with.has_value() && again.has_value());
  EXPECT_EQ(plain->finding_count(), 0U);
  EXPECT_GT(with->finding_count(), 0U);
  ASSERT_EQ(with->pipe_count(), plain->pipe_count());
  for (PipeId p : plain->pipe_ids()) EXPECT_EQ(with->pipe(p), plain->pipe(p));
  EXPECT_TRUE(std::equal(with->findings().begin(), with->findings().end(),
                         again->findings().begin(), again->findings().end()));
  options.findings_per_km = -1;
  EXPECT_FALSE(generate_network(options).has_value());
}

}  // namespace
}  // namespace sewerplan
