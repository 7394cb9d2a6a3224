// SPDX-License-Identifier: MIT
// The motion table (core/passage_motion.h): its JSON form, its errors, stale tables, and the one
// rule that decides a passage with or without it.
#include "sewerplan/core/passage_motion.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "sewerplan/core/map_fingerprint.h"

#include "support/small_map.h"

namespace sewerplan {
namespace {

using testing::SmallMap;

class PassageMotionTest : public ::testing::Test {
 protected:
  SewerMap map_ = SmallMap()
                      .manhole("M1", 0, 0, true)
                      .manhole("M2", 10, 0)
                      .manhole("M3", 10, 10)
                      .manhole("M4", 20, 0)
                      .pipe("P1", "M1", "M2")
                      .pipe("P2", "M2", "M3")
                      .pipe("P3", "M2", "M4")
                      .build();
  RobotProfile profile_ = *builtin_profile("makro-1.1");
  ManholeId m2_ = *map_.find_manhole("M2");

  PassageMotionTable table() const {
    return PassageMotionTable(
        map_geometry_fingerprint(map_), profile_geometry_fingerprint(profile_),
        {PassageMotion{.manhole = m2_,
                       .from = SlotIndex{0},
                       .to = SlotIndex{1},
                       .feasible = true,
                       .duration_s = 41.25,
                       .waypoints = {{-0.5, 0, 0, 0}, {0, 0.1, 0, 45.5}, {0, 2.5, 0.1, 90}}},
         PassageMotion{.manhole = m2_,
                       .from = SlotIndex{1},
                       .to = SlotIndex{0},
                       .feasible = false,
                       .reason = "the step of 0.40 m exceeds the 0.31 m"}});
  }

  Result<PassageMotionTable> read(const std::string& text) {
    diagnostics_ = Diagnostics{};
    return read_passage_motion_json(text, "t.motion.json", map_, diagnostics_);
  }
  Diagnostics diagnostics_;
};

// Issue 14: the fingerprint under a stop condition is the same one, or nothing once it fired.
TEST_F(PassageMotionTest, TheMapFingerprintUnderAStopIsTheSameOrNothing) {
  EXPECT_EQ(map_geometry_fingerprint(map_, StopCondition{}), map_geometry_fingerprint(map_));
  const std::atomic<bool> cancel{true};
  EXPECT_FALSE(map_geometry_fingerprint(map_, StopCondition().with_cancel(cancel)).has_value());
}

TEST_F(PassageMotionTest, RoundTripsThroughJson) {
  std::ostringstream out;
  write_passage_motion_json(table(), map_, out);
  Result<PassageMotionTable> back = read(out.str());
  ASSERT_TRUE(back.has_value()) << back.error();
  EXPECT_EQ(*back, table());
}

TEST_F(PassageMotionTest, FindsPassagesByManholeAndSlots) {
  const PassageMotionTable t = table();
  ASSERT_NE(t.find(m2_, SlotIndex{0}, SlotIndex{1}), nullptr);
  EXPECT_TRUE(t.find(m2_, SlotIndex{0}, SlotIndex{1})->feasible);
  EXPECT_FALSE(t.find(m2_, SlotIndex{1}, SlotIndex{0})->feasible);
  EXPECT_EQ(t.find(m2_, SlotIndex{0}, SlotIndex{2}), nullptr);
}

TEST_F(PassageMotionTest, NamesEveryErrorByJsonPath) {
  const std::string head =
      R"({"format": "sewerplan-passage-motion", "version": 1, "map_fingerprint": "a",
          "profile_fingerprint": "b", "passages": [)";
  Result<PassageMotionTable> t =
      read(head + R"({"manhole": "M9", "from_slot": 1, "to_slot": 2, "feasible": false},
                     {"manhole": "M2", "from_slot": 1, "to_slot": 7, "feasible": false},
                     {"manhole": "M2", "from_slot": 1, "to_slot": 2, "feasible": true,
                      "duration_s": -3},
                     {"manhole": "M2", "from_slot": 1, "to_slot": 3, "feasible": true,
                      "duration_s": 3, "waypoints": [[1, 2, 3]]}]})");
  ASSERT_FALSE(t.has_value());
  const std::string& e = t.error().message;
  EXPECT_NE(e.find("t.motion.json:$.passages[0].manhole: error: unknown manhole 'M9'"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("$.passages[1].to_slot: error: manhole M2 has slots 1 to 3, got 7"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("$.passages[2].duration_s"), std::string::npos) << e;
  EXPECT_NE(e.find("$.passages[3].waypoints[0]"), std::string::npos) << e;

  t = read(head + R"({"manhole": "M2", "from_slot": 1, "to_slot": 2, "feasible": false},
                     {"manhole": "M2", "from_slot": 1, "to_slot": 2, "feasible": false}]})");
  ASSERT_FALSE(t.has_value());
  EXPECT_NE(t.error().message.find("listed more than once"), std::string::npos);

  t = read(R"({"format": "sewerplan-mission", "version": 1})");
  ASSERT_FALSE(t.has_value());
  EXPECT_NE(t.error().message.find("$.format"), std::string::npos);
  t = read("{ not json");
  ASSERT_FALSE(t.has_value());
  EXPECT_EQ(t.error().code, ErrorCode::kParse);
}

TEST_F(PassageMotionTest, AStaleTableIsRefusedWithWhatChanged) {
  const auto dir = std::filesystem::temp_directory_path() / "sewerplan_passage_motion_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "map.motion.json";
  {
    std::ofstream out(path);
    write_passage_motion_json(table(), map_, out);
  }
  EXPECT_TRUE(load_passage_motion(path, map_, profile_).has_value());

  RobotProfile longer = profile_;
  longer.length_m = 2.5;
  Result<PassageMotionTable> t = load_passage_motion(path, map_, longer);
  ASSERT_FALSE(t.has_value());
  EXPECT_NE(t.error().message.find("stale motion table"), std::string::npos);
  EXPECT_NE(t.error().message.find("robot geometry"), std::string::npos) << t.error().message;

  // Times other than the manoeuvre's do not matter; a map with another manhole diameter does.
  RobotProfile faster = profile_;
  faster.speed_mps = 0.5;
  EXPECT_TRUE(load_passage_motion(path, map_, faster).has_value());
  const SewerMap other = SmallMap()
                             .manhole("M1", 0, 0, true)
                             .manhole("M2", 10, 0)
                             .manhole("M3", 10, 10)
                             .manhole("M4", 20, 0)
                             .pipe("P1", "M1", "M2")
                             .pipe("P2", "M2", "M3", 0.4)
                             .pipe("P3", "M2", "M4")
                             .build();
  t = load_passage_motion(path, other, profile_);
  ASSERT_FALSE(t.has_value());
  EXPECT_NE(t.error().message.find("map geometry"), std::string::npos) << t.error().message;
  std::filesystem::remove_all(dir);
}

TEST_F(PassageMotionTest, TheDefaultPathIsBesideTheMap) {
  EXPECT_EQ(default_motion_path("datasets/ais/map.json"), "datasets/ais/map.motion.json");
}

TEST_F(PassageMotionTest, TheTableDecidesItsPassagesAndTheRulesTheOthers) {
  const PassageMotionTable t = table();
  PassageVerdict v = judge_passage(map_, profile_, &t, m2_, SlotIndex{0}, SlotIndex{1});
  EXPECT_TRUE(v.allowed);
  EXPECT_TRUE(v.by_motion);
  EXPECT_EQ(v.duration_s, 41.25);
  v = judge_passage(map_, profile_, &t, m2_, SlotIndex{1}, SlotIndex{0});
  EXPECT_FALSE(v.allowed);
  // Not in the table: the rules. A right angle: 20 s + 90 x 0.3 s.
  v = judge_passage(map_, profile_, &t, m2_, SlotIndex{1}, SlotIndex{2});
  EXPECT_FALSE(v.by_motion);
  EXPECT_TRUE(v.allowed);
  EXPECT_NEAR(v.duration_s, 20 + 90 * 0.3, 1e-9);
  EXPECT_EQ(judge_passage(map_, profile_, nullptr, m2_, SlotIndex{0}, SlotIndex{1}).duration_s,
            20 + v.turn_deg * 0.3);
}

}  // namespace
}  // namespace sewerplan
