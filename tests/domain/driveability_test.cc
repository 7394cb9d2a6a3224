// SPDX-License-Identifier: MIT
#include "sewerplan/domain/driveability.h"

#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/map_io.h"

#include "support/paths.h"
#include "support/small_map.h"

namespace sewerplan::domain {
namespace {

using ::testing::ElementsAre;

SewerMap load(const std::string& relative) {
  Diagnostics d;
  Result<SewerMap> map = read_map(testing::dataset_path(relative), d);
  EXPECT_TRUE(map.has_value()) << (map.has_value() ? "" : map.error().message);
  return map.has_value() ? std::move(map).value() : SewerMap{};
}

template <class Id, class NameOf>
std::vector<std::string> names(const std::vector<Id>& ids, NameOf name_of) {
  std::vector<std::string> out;
  for (Id id : ids) out.push_back(name_of(id));
  return out;
}

std::vector<std::string> pipe_names(const SewerMap& map, const std::vector<PipeId>& ids) {
  return names(ids, [&](PipeId p) { return map.pipe(p).name; });
}
std::vector<std::string> manhole_names(const SewerMap& map, const std::vector<ManholeId>& ids) {
  return names(ids, [&](ManholeId m) { return map.manhole(m).name; });
}

const RobotProfile kMakroPlus = *builtin_profile("makro-plus");

// datasets/isybau/README.md: pipe S4 is 0.25 m; in S2, the passage between pipes S3 and S2 turns
// 116.6 degrees and steps 0.35 m; between S1 and S3 it turns 63.4 and steps exactly 0.30 m.
TEST(Driveability, ReportsPipesPassagesAndReachOfTheIsybauStreet) {
  const SewerMap map = load("isybau/street-2017.xml");
  const DriveabilityReport r = analyse_driveability(map, kMakroPlus, default_starts(map));
  EXPECT_THAT(pipe_names(map, r.too_narrow), ElementsAre("S4"));
  EXPECT_TRUE(r.too_wide.empty());
  EXPECT_EQ(r.passages_checked, 3U);  // the three pairs of slots in S2
  ASSERT_EQ(r.passages.size(), 1U);
  const PassageLimit& p = r.passages[0];
  EXPECT_EQ(map.manhole(p.manhole).name, "S2");
  EXPECT_EQ(p.from, SlotIndex{1});
  EXPECT_EQ(p.to, SlotIndex{2});
  EXPECT_NEAR(p.turn_deg, 116.57, 0.01);
  EXPECT_NEAR(p.step_m, -0.35, 1e-9);
  EXPECT_TRUE(p.turn_exceeded);
  EXPECT_TRUE(p.step_exceeded);
  // The Schachte S1, S2, S3 are the exits; the Bauwerk S4 is reached through pipe S2.
  EXPECT_THAT(manhole_names(map, r.starts), ElementsAre("S1", "S2", "S3"));
  EXPECT_THAT(manhole_names(map, r.reachable_manholes), ElementsAre("S1", "S2", "S3", "S4"));
  EXPECT_THAT(pipe_names(map, r.reachable_pipes), ElementsAre("S1", "S3", "S2"));
  EXPECT_DOUBLE_EQ(r.reachable_length_m, 30 + 44.72 + 30);
}

// A symmetric robot may back out of a pipe: from S4 it reaches S2 by pipe S2, drives on into pipe
// S1, backs out to S2 and turns into S3 (63.4 deg). With steps limited to 0.20 m that last
// passage (0.30 m) is closed, and S3 is out of reach.
TEST(Driveability, ReachesOnlyWhatTheLimitsAllowFromOneStart) {
  const SewerMap map = load("isybau/street-2017.xml");
  const std::vector<ManholeId> start{*map.find_manhole("S4")};
  const DriveabilityReport r = analyse_driveability(map, kMakroPlus, start);
  EXPECT_THAT(manhole_names(map, r.reachable_manholes), ElementsAre("S1", "S2", "S3", "S4"));
  EXPECT_THAT(pipe_names(map, r.reachable_pipes), ElementsAre("S1", "S3", "S2"));
  RobotProfile low_steps = kMakroPlus;
  low_steps.max_step_m = 0.2;
  const DriveabilityReport low = analyse_driveability(map, low_steps, start);
  EXPECT_THAT(manhole_names(map, low.reachable_manholes), ElementsAre("S1", "S2", "S4"));
  EXPECT_THAT(pipe_names(map, low.reachable_pipes), ElementsAre("S1", "S2"));
  EXPECT_EQ(low.passages.size(), 2U);
}

TEST(Driveability, ExplainsWhyMakroCannotDriveMostOfEpaExample1) {
  const SewerMap map = load("swmm/epa-example1.inp");
  const DriveabilityReport r = analyse_driveability(map, kMakroPlus, default_starts(map));
  // [XSECTIONS]: conduits 10, 15, 16, 7 and 8 are 2 ft = 0.6096 m, over MAKRO's 0.60 m.
  EXPECT_THAT(pipe_names(map, r.too_wide), ElementsAre("10", "15", "16", "7", "8"));
  EXPECT_TRUE(r.too_narrow.empty());  // the smallest are 1 ft = 0.3048 m
  EXPECT_EQ(r.reachable_pipes.size(), 13U - 5U);
}

TEST(Driveability, StartsFromTheLargestPartWithoutExits) {
  MapBuilder b("parts");
  b.add_manhole({.name = "A", .diameter_m = 1, .slots = {{.pipe = "AB"}}});
  b.add_manhole({.name = "B",
                 .diameter_m = 1,
                 .slots = {{.pipe = "AB", .azimuth_deg = 180}, {.pipe = "BC"}}});
  b.add_manhole({.name = "C", .diameter_m = 1, .slots = {{.pipe = "BC", .azimuth_deg = 180}}});
  b.add_manhole({.name = "D", .diameter_m = 1, .slots = {{.pipe = "DE"}}});
  b.add_manhole({.name = "E", .diameter_m = 1, .slots = {{.pipe = "DE", .azimuth_deg = 180}}});
  b.add_pipe({.name = "AB", .from = "A", .to = "B", .length_m = 1, .diameter_m = 0.4});
  b.add_pipe({.name = "BC", .from = "B", .to = "C", .length_m = 1, .diameter_m = 0.4});
  b.add_pipe({.name = "DE", .from = "D", .to = "E", .length_m = 1, .diameter_m = 0.4});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  EXPECT_THAT(manhole_names(*map, default_starts(*map)), ElementsAre("A", "B", "C"));
}

}  // namespace
}  // namespace sewerplan::domain

namespace sewerplan::domain {
namespace {

// With a motion table (core/passage_motion.h), its verdicts replace the turn and step limits for
// the passages it has, in either direction; the others keep the rules.
TEST(DriveabilityMotion, TheMotionTableDecidesThePassagesItHas) {
  const SewerMap map = load("ais-testbed/map.json");
  const RobotProfile profile = *builtin_profile("makro-1.1");
  const ManholeId m4 = *map.find_manhole("M4");  // slots 1 and 2: a 116 degree turn
  const ManholeId m7 = *map.find_manhole("M7");  // slots 1 and 2: a 127 degree turn
  const PassageMotionTable table(
      map_geometry_fingerprint(map), profile_geometry_fingerprint(profile),
      {PassageMotion{.manhole = m4, .from = SlotIndex{0}, .to = SlotIndex{1}, .feasible = true},
       PassageMotion{.manhole = m4, .from = SlotIndex{1}, .to = SlotIndex{0}, .feasible = true},
       PassageMotion{.manhole = m7,
                     .from = SlotIndex{1},
                     .to = SlotIndex{0},
                     .feasible = false,
                     .reason = "too tight"}});
  const auto starts = default_starts(map);
  const DriveabilityReport rules = analyse_driveability(map, profile, starts);
  const DriveabilityReport motion = analyse_driveability(map, profile, starts, &table);
  auto listed = [](const DriveabilityReport& r, ManholeId m) {
    for (const PassageLimit& p : r.passages) {
      if (p.manhole == m) return &p;
    }
    return static_cast<const PassageLimit*>(nullptr);
  };
  ASSERT_NE(listed(rules, m4), nullptr);
  EXPECT_EQ(listed(motion, m4), nullptr);  // the planner found motions both ways
  ASSERT_NE(listed(motion, m7), nullptr);
  EXPECT_EQ(listed(motion, m7)->motion_reason, "too tight");
  EXPECT_FALSE(listed(motion, m7)->turn_exceeded);
  EXPECT_EQ(motion.passages.size(), rules.passages.size() - 1);
}

}  // namespace
}  // namespace sewerplan::domain

namespace sewerplan::domain {
namespace {

// Issue 15: a place an inspection finding closes (a collapse) is closed as the planner closes it,
// and what it cuts off from the starts is listed.
TEST(Driveability, FindingClosuresCutOffWhatLiesBehindThem) {
  const SewerMap map = testing::SmallMap()
                           .manhole("A", 0, 0, /*exit=*/true)
                           .manhole("B", 10, 0)
                           .manhole("C", 20, 0)
                           .manhole("D", 30, 0)
                           .pipe("P1", "A", "B")
                           .pipe("P2", "B", "C")
                           .pipe("P3", "C", "D")
                           .build();
  const RobotProfile profile = *builtin_profile("makro-1.1");
  const std::vector<ManholeId> starts = default_starts(map);
  const DriveabilityReport open = analyse_driveability(map, profile, starts);
  EXPECT_EQ(open.reachable_manholes.size(), 4U);
  EXPECT_TRUE(open.cut_off_manholes.empty());
  const std::vector<Blockage> closures{{.pipe = *map.find_pipe("P2"), .offset_m = 5}};
  const DriveabilityReport closed = analyse_driveability(map, profile, starts, nullptr, closures);
  EXPECT_EQ(closed.closures, closures);
  EXPECT_THAT(closed.cut_off_manholes, ElementsAre(*map.find_manhole("C"), *map.find_manhole("D")));
  // P2 is still driven up to the collapse; P3 lies wholly behind it.
  EXPECT_THAT(closed.cut_off_pipes, ElementsAre(*map.find_pipe("P3")));
  EXPECT_EQ(closed.reachable_manholes.size(), 2U);
}

}  // namespace
}  // namespace sewerplan::domain
