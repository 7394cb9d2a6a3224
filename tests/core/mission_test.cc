// SPDX-License-Identifier: MIT
#include "sewerplan/core/mission.h"

#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/text_file.h"

#include "support/paths.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;

class MissionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Diagnostics d;
    Result<SewerMap> map = read_map(testing::dataset_path("ais-testbed/map.json"), d);
    ASSERT_TRUE(map.has_value()) << map.error();
    map_ = std::move(*map);
  }

  Result<Mission> read(std::string_view text) {
    diagnostics_ = Diagnostics{};
    return read_mission_json(text, "m.json", map_, diagnostics_);
  }

  SewerMap map_;
  Diagnostics diagnostics_;
};

TEST_F(MissionTest, ReadsThePapersMission) {
  Diagnostics d;
  Result<Mission> m =
      read_mission(testing::dataset_path("ais-testbed/missions/paper.json"), map_, d);
  ASSERT_TRUE(m.has_value()) << m.error();
  EXPECT_EQ(m->profile.name, "makro-1.1");
  EXPECT_EQ(std::get<PipeSpot>(m->start).pipe, *map_.find_pipe("P12"));
  ASSERT_EQ(m->tasks.size(), 3U);
  EXPECT_EQ(m->tasks[0].kind, TaskKind::kTakeWaterSample);
  EXPECT_EQ(describe(m->tasks[0].place, map_), "point W1 (pipe P6)");
  EXPECT_EQ(m->tasks[1].kind, TaskKind::kInspectPipe);
  ASSERT_NE(m->final_task(), nullptr);
  EXPECT_EQ(describe(m->final_task()->place, map_), "pipe P9");
  // Exits default to the manholes marked exit in the map.
  EXPECT_EQ(m->exits.size(), 4U);
}

TEST_F(MissionTest, RoundTripsThroughJson) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1,
    "profile": {"base": "makro-plus", "speed_mps": 0.5}, "start": {"manhole": "M1"},
    "tasks": [{"type": "inspect_area", "name": "area", "pipes": ["P1", "P5"]},
              {"type": "go_to", "at": {"pipe": "P6", "offset_m": 1.5}}],
    "exits": ["M10"], "battery_reserve": 0.3,
    "closed": {"pipes": ["P2"], "passages": [{"manhole": "M6", "from_slot": 3, "to_slot": 4}]}})");
  ASSERT_TRUE(m.has_value()) << m.error();
  ASSERT_EQ(m->tasks.size(), 3U);
  EXPECT_EQ(m->tasks[0].name, "area/P1");
  EXPECT_EQ(m->tasks[2].name, "task-2");
  EXPECT_DOUBLE_EQ(m->profile.speed_mps, 0.5);
  EXPECT_DOUBLE_EQ(m->profile.battery_wh, 480);
  ASSERT_EQ(m->closed_passages.size(), 1U);
  EXPECT_EQ(m->closed_passages[0].from, SlotIndex{2});
  std::ostringstream out;
  write_mission_json(*m, map_, out);
  Result<Mission> again = read(out.str());
  ASSERT_TRUE(again.has_value()) << again.error() << "\n" << out.str();
  EXPECT_EQ(*again, *m);
}

// Each task kind is written by its name (to_string) and read back as itself; its name is read
// exactly.
TEST_F(MissionTest, EveryTaskKindRoundTripsThroughItsName) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"manhole": "M1"},
    "tasks": [{"type": "go_to", "at": {"manhole": "M6"}},
              {"type": "inspect_pipe", "pipe": "P4"},
              {"type": "take_water_sample", "at": {"pipe": "P6", "offset_m": 1.5}}]})");
  ASSERT_TRUE(m.has_value()) << m.error();
  ASSERT_EQ(m->tasks.size(), 3U);
  EXPECT_EQ(m->tasks[0].kind, TaskKind::kGoTo);
  EXPECT_EQ(m->tasks[1].kind, TaskKind::kInspectPipe);
  EXPECT_EQ(m->tasks[2].kind, TaskKind::kTakeWaterSample);
  std::ostringstream out;
  write_mission_json(*m, map_, out);
  Result<Mission> again = read(out.str());
  ASSERT_TRUE(again.has_value()) << again.error() << "\n" << out.str();
  EXPECT_EQ(*again, *m);
  Result<Mission> bad = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"manhole": "M1"}, "tasks": [{"type": "Go_To", "at": {"manhole": "M6"}}]})");
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message, HasSubstr("m.json:$.tasks[0].type: error: unknown task type"));
}

TEST_F(MissionTest, NamesEveryUnknownObjectByJsonPath) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"pipe": "P99"},
    "tasks": [{"type": "take_water_sample", "at": {"point": "W7"}},
              {"type": "inspect_pipe", "pipe": "P4"},
              {"type": "fly", "at": {"manhole": "M1"}}],
    "exits": ["M77"]})");
  ASSERT_FALSE(m.has_value());
  EXPECT_EQ(m.error().code, ErrorCode::kInvalidMission);
  const std::string& e = m.error().message;
  EXPECT_THAT(e, HasSubstr("m.json:$.start.pipe: error: unknown pipe 'P99'"));
  EXPECT_THAT(e, HasSubstr("m.json:$.tasks[0].at.point: error: unknown inspection point 'W7'"));
  EXPECT_THAT(e, HasSubstr("m.json:$.tasks[2].type: error: unknown task type 'fly' "
                           "(go_to, inspect_pipe, take_water_sample, inspect_area)"));
  EXPECT_THAT(e, HasSubstr("m.json:$.exits[0]: error: unknown manhole 'M77'"));
  // A follow-on "no exit" error would only repeat the unknown name.
  EXPECT_THAT(e, ::testing::Not(HasSubstr("the mission has no exit")));
}

// Issue 33: a misspelt field is refused, not warned about and left at its default (a mission with
// "batery_reserve" ran on the default reserve; in the station, whose /plan shows no warnings,
// without a word). Every unknown field of every object is named at its path, with the fields known.
TEST_F(MissionTest, Issue33RefusesEveryUnknownFieldNamingTheFieldsKnown) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"manhole": "M1", "ofset_m": 2}, "batery_reserve": 0.5,
    "tasks": [{"type": "go_to", "at": {"manhole": "M6"}, "finall": true}],
    "closed": {"pipes": ["P2"], "passage": [],
               "blockages": [{"pipe": "P3", "offset_m": 1, "note": "x"}]},
    "exits": ["M10"]})");
  ASSERT_FALSE(m.has_value());
  EXPECT_EQ(m.error().code, ErrorCode::kInvalidMission);
  const std::string& e = m.error().message;
  EXPECT_THAT(e, HasSubstr("m.json:$.batery_reserve: error: unknown field 'batery_reserve' "
                           "(expected format, version, name, profile, start, tasks, exits, "
                           "battery_reserve, closed)"));
  EXPECT_THAT(e, HasSubstr("m.json:$.start.ofset_m: error: unknown field 'ofset_m' (expected "
                           "manhole, pipe, point, offset_m)"));
  EXPECT_THAT(e, HasSubstr("m.json:$.tasks[0].finall: error: unknown field 'finall' (expected "
                           "name, type, at, pipe, pipes, final)"));
  EXPECT_THAT(e, HasSubstr("m.json:$.closed.passage: error: unknown field 'passage' (expected "
                           "pipes, passages, blockages)"));
  EXPECT_THAT(e, HasSubstr("m.json:$.closed.blockages[0].note: error: unknown field 'note' "
                           "(expected pipe, offset_m)"));
  Result<Mission> passage = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"manhole": "M1"}, "tasks": [{"type": "go_to", "at": {"manhole": "M6"}}],
    "closed": {"passages": [{"manhole": "M6", "from_slot": 3, "to_slot": 4, "too": 1}]}})");
  ASSERT_FALSE(passage.has_value());
  EXPECT_THAT(passage.error().message,
              HasSubstr("m.json:$.closed.passages[0].too: error: unknown field 'too' (expected "
                        "manhole, from_slot, to_slot)"));
}

// Issue 31: a number beyond a double in a mission is named by file, line and column.
TEST_F(MissionTest, Issue31NamesTheLineOfANumberBeyondADouble) {
  Result<Mission> m = read(
      "{\"format\": \"sewerplan-mission\", \"version\": 1,\n"
      " \"battery_wh\": 1e999}");
  ASSERT_FALSE(m.has_value());
  EXPECT_THAT(m.error().message, HasSubstr("m.json:2:16: error: number 1e999 is out of range"));
}

TEST_F(MissionTest, AFieldGivenTwiceIsAnError) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"pipe": "P12", "pipe": "P4"},
    "tasks": [{"type": "inspect_pipe", "pipe": "P4"}]})");
  ASSERT_FALSE(m.has_value());
  EXPECT_THAT(m.error().message, HasSubstr("m.json:$.start.pipe: error: field 'pipe' given twice"));
}

// Issue 33: a mission parsed already, inside a larger document (a request's body), is read by the
// same reader with the same checks, each problem at its path in that document.
TEST_F(MissionTest, ReadsAMissionParsedAlreadyAtItsPath) {
  Diagnostics d;
  const std::optional<JsonDocument> body = JsonDocument::parse(
      R"({"runs": 3, "mission": {"format": "sewerplan-mission", "version": 1, "start": {"pipe": "P12"},
          "tasks": [{"type": 3}, {"type": "inspect_pipe",
          "pipe": "P99"}], "closed": {"pipes": [7]}}})",
      "body", d);
  ASSERT_TRUE(body.has_value()) << d.error_summary();
  Result<Mission> m =
      read_mission_value(body->root()["mission"].value(), "$.mission", "body", map_, d);
  ASSERT_FALSE(m.has_value());
  EXPECT_EQ(m.error().code, ErrorCode::kInvalidMission);
  EXPECT_THAT(m.error().message,
              HasSubstr("body:$.mission.tasks[0].type: error: expected a string, got 3"));
  EXPECT_THAT(m.error().message,
              HasSubstr("body:$.mission.tasks[1].pipe: error: unknown pipe 'P99'"));
  EXPECT_THAT(m.error().message,
              HasSubstr("body:$.mission.closed.pipes[0]: error: expected a name"));
  // The same mission read from its own text: the same messages at the file's paths.
  Result<Mission> whole = read(
      R"({"format": "sewerplan-mission", "version": 1, "start": {"pipe": "P12"},
          "tasks": [{"type": 3}]})");
  ASSERT_FALSE(whole.has_value());
  EXPECT_THAT(whole.error().message, HasSubstr("m.json:$.tasks[0].type: error: expected a string"));
}

// Issue 33: a text refused whole for a key given twice anywhere (a request's body), in the text's
// order, the first ones named and the rest counted; and a parse with a depth of its own, which
// says where the first level too deep opens.
TEST(JsonFields, ReportsRepeatedKeysAnywhereAndADepthOfItsOwn) {
  Diagnostics d;
  const std::optional<JsonDocument> doc = JsonDocument::parse(
      R"({"a": [{"b": 1, "b": 2}], "c": {"d": {"e": 1, "e": 2, "e": 3}}, "a": 0})", "t", d);
  ASSERT_TRUE(doc.has_value());
  EXPECT_EQ(report_repeated_keys(doc->root(), "$", "t", d, 3), 4u);
  EXPECT_EQ(d.error_summary(),
            "t:$.a[0].b: error: field 'b' given twice in one object: which value is meant is "
            "unclear\n"
            "t:$.c.d.e: error: field 'e' given twice in one object: which value is meant is "
            "unclear\n"
            "t:$.c.d.e: error: field 'e' given twice in one object: which value is meant is "
            "unclear\n"
            "t: error: (1 more fields given twice)");
  Diagnostics none;
  const std::optional<JsonDocument> fine = JsonDocument::parse(R"({"a": {"a": 1}})", "t", none);
  ASSERT_TRUE(fine.has_value());
  EXPECT_EQ(report_repeated_keys(fine->root(), "$", "t", none, 3), 0u);
  EXPECT_FALSE(none.has_errors());
  // Four levels pass a limit of four; the fifth is refused where it opens.
  Diagnostics deep;
  EXPECT_TRUE(JsonDocument::parse("[[[[1]]]]", "t", deep, 4).has_value()) << deep.error_summary();
  EXPECT_FALSE(JsonDocument::parse("\n [[[{\"[\": [[]]}]]]", "t", deep, 4).has_value());
  EXPECT_EQ(deep.error_summary(),
            "t:2:11: error: the JSON nests arrays and objects more than 4 levels deep");
}

// Windows editors start a UTF-8 file with a byte order mark; it is no JSON value, but no error.
TEST_F(MissionTest, ReadsAFileThatStartsWithAByteOrderMark) {
  Result<std::string> text =
      read_text_file(testing::dataset_path("ais-testbed/missions/paper.json"));
  ASSERT_TRUE(text.has_value());
  Result<Mission> m = read("\xEF\xBB\xBF" + *text);
  ASSERT_TRUE(m.has_value()) << m.error();
  EXPECT_EQ(m->tasks.size(), 3U);
}

TEST_F(MissionTest, RejectsInconsistentMissions) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1,
    "start": {"manhole": "M1"}, "exits": [],
    "tasks": [{"name": "a", "type": "go_to", "at": {"pipe": "P1", "offset_m": 99}},
              {"name": "a", "type": "take_water_sample", "at": {"manhole": "M2"}}],
    "battery_reserve": 1.5})");
  ASSERT_FALSE(m.has_value());
  const std::string& e = m.error().message;
  EXPECT_THAT(e, HasSubstr("offset 99 m is outside pipe P1 (0 to 8.485 m)"));
  EXPECT_THAT(e, HasSubstr("a water sample is taken in a pipe, not in a manhole"));
  EXPECT_THAT(e, HasSubstr("battery_reserve: error: must be a fraction from 0 to below 1"));
  EXPECT_THAT(e, HasSubstr("the mission has no exit"));
}

// "exits": "map" (the default) takes the map's 4 exit manholes, "all" every manhole with a pipe
// (all 12 of the test bed), anything else is an error at $.exits.
TEST_F(MissionTest, ChoosesExitsFromTheMapAllManholesOrANamedList) {
  auto with_exits = [&](std::string_view exits) {
    return read(std::string(R"({"format": "sewerplan-mission", "version": 1,
      "start": {"manhole": "M1"}, "tasks": [])") +
                (exits.empty() ? "" : ", \"exits\": " + std::string(exits)) + "}");
  };
  Result<Mission> by_default = with_exits("");
  ASSERT_TRUE(by_default.has_value()) << by_default.error();
  EXPECT_EQ(by_default->exits.size(), 4U);
  Result<Mission> from_map = with_exits(R"("map")");
  ASSERT_TRUE(from_map.has_value());
  EXPECT_EQ(from_map->exits, by_default->exits);
  Result<Mission> all = with_exits(R"("all")");
  ASSERT_TRUE(all.has_value());
  EXPECT_EQ(all->exits.size(), 12U);
  Result<Mission> named = with_exits(R"(["M3"])");
  ASSERT_TRUE(named.has_value());
  EXPECT_EQ(named->exits, std::vector<ManholeId>{*map_.find_manhole("M3")});
  Result<Mission> bad = with_exits(R"("outfalls")");
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message,
              HasSubstr("m.json:$.exits: error: expected an array of manhole names, \"map\" or "
                        "\"all\", got \"outfalls\""));
}

TEST_F(MissionTest, RejectsAnUnknownOrImpossibleProfile) {
  Result<Mission> m = read(R"({"format": "sewerplan-mission", "version": 1, "profile": "makro-3",
    "start": {"manhole": "M1"}, "tasks": []})");
  ASSERT_FALSE(m.has_value());
  EXPECT_THAT(m.error().message,
              HasSubstr("unknown robot profile 'makro-3' (built in: makro-1.1, makro-plus)"));
  m = read(R"({"format": "sewerplan-mission", "version": 1,
    "profile": {"speed_mps": -1, "min_pipe_diameter_m": 0.7, "battery_wh": 1e300},
    "start": {"manhole": "M1"}, "tasks": []})");
  ASSERT_FALSE(m.has_value());
  EXPECT_THAT(m.error().message, HasSubstr("speed_mps = -1: must be from 0.001 to 100 m/s"));
  // Beyond core/limits.h: plan costs would not fit the planner's integer milliseconds.
  EXPECT_THAT(m.error().message, HasSubstr("battery_wh = 1e+300: must be above 0 and at most 1e6"));
  EXPECT_THAT(m.error().message,
              HasSubstr("max_pipe_diameter_m = 0.6: must be at least min_pipe_diameter_m"));
}

TEST(RobotProfile, BuiltInProfilesMatchThePaper) {
  const RobotProfile makro = *builtin_profile("makro-1.1");
  const RobotProfile plus = *builtin_profile("makro-plus");
  EXPECT_DOUBLE_EQ(makro.speed_mps, 0.30);
  EXPECT_DOUBLE_EQ(plus.speed_mps, 0.60);
  EXPECT_DOUBLE_EQ(makro.battery_wh / makro.power_w, 2.0) << "about two hours";
  EXPECT_DOUBLE_EQ(plus.battery_wh / plus.power_w, 4.0) << "twice as long";
  for (const RobotProfile& p : {makro, plus}) {
    EXPECT_DOUBLE_EQ(p.min_pipe_diameter_m, 0.30);
    EXPECT_DOUBLE_EQ(p.max_pipe_diameter_m, 0.60);
    EXPECT_DOUBLE_EQ(p.max_step_m, 0.30);
    EXPECT_DOUBLE_EQ(p.max_turn_deg, 90);
    EXPECT_DOUBLE_EQ(p.length_m, 2.0);
    EXPECT_EQ(p.segment_count, 6);
    EXPECT_TRUE(p.symmetric);
    EXPECT_TRUE(validate_profile(p).has_value());
  }
  EXPECT_FALSE(builtin_profile("makro-2").has_value());
}

TEST(RobotProfile, LoadsAProfileFileOrNamesWhyNot) {
  Result<RobotProfile> p = load_profile("no-such-profile.json");
  ASSERT_FALSE(p.has_value());
  EXPECT_THAT(p.error().message, HasSubstr("'no-such-profile.json' is neither a built-in profile"));
  Diagnostics d;
  p = read_profile_json(R"({"base": "makro-plus", "name": "fast", "max_turn_deg": 60})", "p.json",
                        d);
  ASSERT_TRUE(p.has_value()) << p.error();
  EXPECT_EQ(p->name, "fast");
  EXPECT_DOUBLE_EQ(p->max_turn_deg, 60);
  EXPECT_DOUBLE_EQ(p->speed_mps, 0.60);
}

}  // namespace
}  // namespace sewerplan
