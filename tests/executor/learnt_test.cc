// SPDX-License-Identifier: MIT
// What the robot learnt (executor/learnt.h): kept by the Replanner apart from the operator's
// mission, saved and read back, and a second mission that starts from it.
#include "sewerplan/executor/learnt.h"

#include <gtest/gtest.h>

#include "sewerplan/executor/replanner.h"

#include "support/ais_testbed.h"

namespace sewerplan::executor {
namespace {

TEST(Learnt, FailuresAreLearntApartFromTheOperatorsMissionAndReadBackEqual) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  const PipeId p4 = *ais.map.find_pipe("P4");
  const PipeId p6 = *ais.map.find_pipe("P6");
  const ManholeId m8 = *ais.map.find_manhole("M8");
  (void)replanner.report_failure({.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = 1.5});
  (void)replanner.report_failure(
      {.kind = Failure::Kind::kDangerInPipe, .pipe = p6, .offset_m = 2.25});
  (void)replanner.report_failure({.kind = Failure::Kind::kDangerousPassage,
                                  .manhole = m8,
                                  .from = SlotIndex{0},
                                  .to = SlotIndex{1}});
  const Learnt& learnt = replanner.learnt();
  EXPECT_EQ(learnt.blockages, (std::vector<Blockage>{{p4, 1.5}}));
  EXPECT_EQ(learnt.danger_spots, (std::vector<Blockage>{{p6, 2.25}}));
  EXPECT_EQ(learnt.closed_passages, (std::vector<ClosedPassage>{{m8, SlotIndex{0}, SlotIndex{1}}}));
  Diagnostics d;
  const auto back = read_learnt_json(learnt_json(learnt, ais.map), "learnt.json", ais.map, d);
  ASSERT_TRUE(back.has_value()) << d.error_summary();
  EXPECT_EQ(*back, learnt);
}

TEST(Learnt, ASecondMissionStartsFromWhatTheFirstLearnt) {
  const auto ais = testing::load_ais_testbed();
  const PipeId p4 = *ais.map.find_pipe("P4");
  Replanner first(ais.map, ais.mission);
  const PlanResponse r = first.report_failure(
      {.kind = Failure::Kind::kBlockage, .pipe = p4, .offset_m = ais.map.pipe(p4).length_m / 2});
  ASSERT_EQ(r.newly_dropped.size(), 1U);  // the inspection of P4
  Replanner second(ais.map, ais.mission);
  ASSERT_TRUE(second.learn(first.learnt()).has_value());
  const PlanResponse plan = second.plan();
  EXPECT_EQ(plan.plan.steps, r.plan.steps);
  EXPECT_EQ(plan.decision, PlanResponse::Decision::kDegraded);
  EXPECT_EQ(second.learnt(), first.learnt());
  // The operator's mission is not where it went.
  EXPECT_TRUE(ais.mission.blockages.empty());
}

TEST(Learnt, ErrorsNameTheFileAndThePath) {
  const auto ais = testing::load_ais_testbed();
  const std::vector<std::pair<std::string, std::string>> bad{
      {R"({"format": "sewerplan-learnt", "version": 1, "blockages": [{"pipe": "P99", "offset_m": 1}]})",
       "learnt.json:$.blockages[0].pipe: error: unknown pipe \"P99\""},
      {R"({"format": "sewerplan-learnt", "version": 1, "danger": [{"pipe": "P4", "offset_m": 1e9}]})",
       "learnt.json:$.danger[0].offset_m"},
      {R"({"format": "sewerplan-learnt", "version": 1,
           "closed_passages": [{"manhole": "M8", "from_slot": 1, "to_slot": 9}]})",
       "learnt.json:$.closed_passages[0].to_slot"},
      {R"({"format": "sewerplan-learnt", "version": 3})", "learnt.json:$.version"},
      {R"({"format": "sewerplan-learnt", "version": 1, "bogus": []})", "learnt.json:$.bogus"},
      {"{\n  \"format\": ", "learnt.json:2:"},
      // Wrong types name the field and the value found.
      {R"({"format": "sewerplan-learnt", "version": 1, "blockages": [{"pipe": 5, "offset_m": 1}]})",
       "learnt.json:$.blockages[0].pipe: error: expected a string, got 5"},
      {R"({"format": "sewerplan-learnt", "version": 1, "danger": [{"pipe": "P4", "offset_m": "1"}]})",
       "learnt.json:$.danger[0].offset_m: error: expected a number, got \"1\""},
      {R"({"format": "sewerplan-learnt", "version": 1, "danger": [3]})",
       "learnt.json:$.danger[0]: error: expected an object, got 3"},
      {R"({"format": "sewerplan-learnt", "version": 1, "blockages": {}})",
       "learnt.json:$.blockages: error: expected an array, got an object"},
      {R"({"format": "sewerplan-learnt", "version": 1,
           "closed_passages": [{"manhole": "M8", "from_slot": 1.5, "to_slot": 2}]})",
       "learnt.json:$.closed_passages[0].from_slot: error: expected a slot of manhole M8"},
      {R"({"format": "sewerplan-learnt", "version": 1, "blockages": [{"offset_m": 1}]})",
       "learnt.json:$.blockages[0]: error: missing required field 'pipe'"},
      {R"({"format": "sewerplan-faults", "version": 1})", "learnt.json:$.format: error: expected"},
      {"[]", "learnt.json:$: error: expected an object, got an array"},
      {"{\"version\": 1" + std::string(400, '4') + "}", "learnt.json:1:13: error: number 1444"},
  };
  for (const auto& [text, where] : bad) {
    Diagnostics d;
    const auto learnt = read_learnt_json(text, "learnt.json", ais.map, d);
    ASSERT_FALSE(learnt.has_value()) << text;
    EXPECT_NE(learnt.error().message.find(where), std::string::npos) << learnt.error().message;
  }
}

// A header of the wrong type, or none, is one error, not two.
TEST(Learnt, AWrongOrMissingHeaderIsOneError) {
  const auto ais = testing::load_ais_testbed();
  for (const std::string text :
       {R"({"format": 5, "version": 1})", R"({"version": 1})",
        R"({"format": "sewerplan-learnt", "version": "1"})", R"({"format": "sewerplan-learnt"})"}) {
    Diagnostics d;
    ASSERT_FALSE(read_learnt_json(text, "learnt.json", ais.map, d).has_value()) << text;
    EXPECT_EQ(d.error_count(), 1u) << text;
  }
}

TEST(Learnt, AReplannerRefusesKnowledgeThatDoesNotFitItsMap) {
  const auto ais = testing::load_ais_testbed();
  Replanner replanner(ais.map, ais.mission);
  Learnt bad;
  bad.blockages.push_back({PipeId{999}, 1.0});
  EXPECT_FALSE(replanner.learn(bad).has_value());
  EXPECT_TRUE(replanner.learnt().empty());
  EXPECT_TRUE(replanner.mission().blockages.empty());
}

}  // namespace
}  // namespace sewerplan::executor
