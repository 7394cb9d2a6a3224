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
      {R"({"format": "sewerplan-learnt", "version": 5})", "learnt.json:$.version"},
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

// The topological filter's memory of the pipes (Learnt::junctions, issue 29): saved with what the
// robot learnt as "junction_memory" and read back equal.
localisation::JunctionMemory p4_memory(const SewerMap& map) {
  const PipeId p4 = *map.find_pipe("P4");
  const double length = map.pipe(p4).length_m;
  return {
      .junctions =
          {{.pipe = p4, .from_end = 1, .distance_m = length / 2, .var_m2 = 0.25, .sightings = 2}},
      .driven = {{.pipe = p4, .from_end = 0, .from_m = 0, .to_m = length / 4},
                 {.pipe = p4, .from_end = 1, .from_m = 0.5, .to_m = length / 2}},
      .mouths = {{.manhole = *map.find_manhole("M2"),
                  .azimuth_deg = 271.5,
                  .invert_z_m = -3.25,
                  .diameter_m = 0.2,
                  .sightings = 3}}};
}

TEST(Learnt, TheJunctionMemoryIsSavedAndReadBackEqual) {
  const auto ais = testing::load_ais_testbed();
  Learnt learnt;
  learnt.blockages.push_back({*ais.map.find_pipe("P6"), 1.0});
  learnt.junctions = p4_memory(ais.map);
  const std::string text = learnt_json(learnt, ais.map);
  EXPECT_NE(text.find("\"from_end\": \"to\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"sd_m\": 0.5"), std::string::npos) << text;
  Diagnostics d;
  const auto back = read_learnt_json(text, "learnt.json", ais.map, d);
  ASSERT_TRUE(back.has_value()) << d.error_summary();
  EXPECT_EQ(*back, learnt);
  // A Replanner keeps it; a Learnt without one (a failure reported later) leaves it as it was.
  Replanner replanner(ais.map, ais.mission);
  ASSERT_TRUE(replanner.learn(learnt).has_value());
  ASSERT_TRUE(replanner.learn(Learnt{.blockages = {{*ais.map.find_pipe("P4"), 1.0}}}).has_value());
  EXPECT_EQ(replanner.learnt().junctions, learnt.junctions);
}

TEST(Learnt, AnOlderFileWithoutAJunctionMemoryStillReads) {
  const auto ais = testing::load_ais_testbed();
  for (
      const char* text :
      {R"({"format": "sewerplan-learnt", "version": 1, "blockages": [{"pipe": "P4", "offset_m": 1}]})",
       R"({"format": "sewerplan-learnt", "version": 2, "blockages": [], "hazards": []})",
       R"({"format": "sewerplan-learnt", "version": 3})",
       R"({"format": "sewerplan-learnt", "version": 3, "junction_memory": {"junctions": []}})"}) {
    Diagnostics d;
    const auto learnt = read_learnt_json(text, "learnt.json", ais.map, d);
    ASSERT_TRUE(learnt.has_value()) << text << ": " << d.error_summary();
    EXPECT_TRUE(learnt->junctions.empty()) << text;
  }
}

TEST(Learnt, ABadJunctionMemoryIsNamedByFileAndPath) {
  const auto ais = testing::load_ais_testbed();
  const auto file = [](const std::string& memory) {
    return R"({"format": "sewerplan-learnt", "version": 4, "junction_memory": )" + memory + "}";
  };
  const std::vector<std::pair<std::string, std::string>> bad{
      {file(R"({"junctions": [{"pipe": "P99", "from_end": "from", "distance_m": 1, "sd_m": 0.5,
               "sightings": 1}]})"),
       "learnt.json:$.junction_memory.junctions[0].pipe: error: unknown pipe \"P99\""},
      {file(R"({"junctions": [{"pipe": "P4", "from_end": "up", "distance_m": 1, "sd_m": 0.5,
               "sightings": 1}]})"),
       "learnt.json:$.junction_memory.junctions[0].from_end: error: expected \"from\" or \"to\""},
      {file(R"({"junctions": [{"pipe": "P4", "from_end": "to", "distance_m": 1e9, "sd_m": 0.5,
               "sightings": 1}]})"),
       "learnt.json:$.junction_memory.junctions[0].distance_m: error: expected a distance from 0"},
      {file(R"({"junctions": [{"pipe": "P4", "from_end": "to", "distance_m": 1, "sd_m": 0,
               "sightings": 1}]})"),
       "learnt.json:$.junction_memory.junctions[0].sd_m: error: expected a standard deviation"},
      {file(R"({"junctions": [{"pipe": "P4", "from_end": "to", "distance_m": 1, "sd_m": 0.5,
               "sightings": 0}]})"),
       "learnt.json:$.junction_memory.junctions[0].sightings: error: expected at least 1"},
      {file(R"({"junctions": [{"pipe": "P4", "from_end": "to", "distance_m": 1, "sd_m": 0.5}]})"),
       "learnt.json:$.junction_memory.junctions[0]: error: missing required field 'sightings'"},
      {file(R"({"driven": [{"pipe": "P4", "from_end": "from", "from_m": 2, "to_m": 1}]})"),
       "learnt.json:$.junction_memory.driven[0].to_m: error: expected more than from_m"},
      {file(R"({"driven": [{"pipe": "P4", "from_end": "from", "from_m": -1, "to_m": 1}]})"),
       "learnt.json:$.junction_memory.driven[0].from_m: error: expected a distance from 0"},
      {file(R"({"driven": [], "known": []})"), "learnt.json:$.junction_memory.known"},
      {file(R"([])"), "learnt.json:$.junction_memory"},
      {R"({"format": "sewerplan-learnt", "version": 2, "junction_memory": {}})",
       "learnt.json:$.junction_memory: error: a junction memory needs version 3"},
      {R"({"format": "sewerplan-learnt", "version": 3, "junction_memory": {"mouths": []}})",
       "learnt.json:$.junction_memory.mouths: error: remembered mouths need version 4"},
      {file(R"({"mouths": [{"manhole": "M99", "azimuth_deg": 10, "invert_z_m": 0,
               "diameter_m": 0.3, "sightings": 1}]})"),
       "learnt.json:$.junction_memory.mouths[0].manhole: error: unknown manhole \"M99\""},
      {file(R"({"mouths": [{"manhole": "M2", "azimuth_deg": 360, "invert_z_m": 0,
               "diameter_m": 0.3, "sightings": 1}]})"),
       "learnt.json:$.junction_memory.mouths[0].azimuth_deg: error: expected a direction in [0, "
       "360)"},
      {file(R"({"mouths": [{"manhole": "M2", "azimuth_deg": 10, "invert_z_m": 0,
               "diameter_m": -0.3, "sightings": 1}]})"),
       "learnt.json:$.junction_memory.mouths[0].diameter_m: error: expected a size above 0 m"},
      {file(R"({"mouths": [{"manhole": "M2", "azimuth_deg": 10, "invert_z_m": null,
               "diameter_m": 0.3, "sightings": 1}]})"),
       "learnt.json:$.junction_memory.mouths[0].invert_z_m"},
      {file(R"({"mouths": [{"manhole": "M2", "azimuth_deg": 10, "invert_z_m": 0,
               "diameter_m": 0.3, "sightings": 0}]})"),
       "learnt.json:$.junction_memory.mouths[0].sightings: error: expected at least 1"},
  };
  for (const auto& [text, where] : bad) {
    Diagnostics d;
    const auto learnt = read_learnt_json(text, "learnt.json", ais.map, d);
    ASSERT_FALSE(learnt.has_value()) << text;
    EXPECT_NE(learnt.error().message.find(where), std::string::npos) << learnt.error().message;
  }
  // The same through the library: learn() refuses it, naming what is wrong, and learns nothing.
  Replanner replanner(ais.map, ais.mission);
  Learnt learnt;
  learnt.junctions = p4_memory(ais.map);
  learnt.junctions.junctions.front().distance_m = -1;
  const auto refused = replanner.learn(learnt);
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("remembered junction 1 in P4: distance -1 m"),
            std::string::npos)
      << refused.error().message;
  EXPECT_TRUE(replanner.learnt().empty());
}

}  // namespace
}  // namespace sewerplan::executor
