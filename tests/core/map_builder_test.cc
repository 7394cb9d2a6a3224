// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/limits.h"
#include "sewerplan/core/map_queries.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;

// M1 -P1- M2 -P2- M3, with M2 a straight-through TYPE_2 manhole and a 0.1 m step into P2.
MapBuilder three_manholes() {
  MapBuilder b("line");
  b.add_manhole({.name = "M1", .diameter_m = 1.0, .exit = true, .slots = {{.pipe = "P1"}}});
  b.add_manhole({.name = "M2",
                 .position = {10, 0, 0},
                 .diameter_m = 1.0,
                 .slots = {{.pipe = "P1", .azimuth_deg = 180},
                           {.pipe = "P2", .azimuth_deg = 0, .invert_z_m = 0.1}}});
  b.add_manhole({.name = "M3",
                 .position = {20, 0, 0},
                 .diameter_m = 1.0,
                 .slots = {{.pipe = "P2", .azimuth_deg = 180}}});
  b.add_pipe({.name = "P1", .from = "M1", .to = "M2", .length_m = 10, .diameter_m = 0.6});
  b.add_pipe({.name = "P2", .from = "M2", .to = "M3", .length_m = 10, .diameter_m = 0.6});
  return b;
}

// A reader may hand a manhole's slots one by one after it (add_slot): the same map.
TEST(MapBuilder, SlotsHandedOneByOneBuildTheSameMap) {
  MapBuilder b("line");
  b.add_manhole({.name = "M1", .diameter_m = 1.0, .exit = true});
  b.add_slot({.pipe = "P1"});
  b.add_manhole({.name = "M2",
                 .position = {10, 0, 0},
                 .diameter_m = 1.0,
                 .slots = {{.pipe = "P1", .azimuth_deg = 180}}});
  b.add_slot({.pipe = "P2", .azimuth_deg = 0, .invert_z_m = 0.1});
  b.add_manhole({.name = "M3", .position = {20, 0, 0}, .diameter_m = 1.0});
  b.add_slot({.pipe = "P2", .azimuth_deg = 180});
  b.add_pipe({.name = "P1", .from = "M1", .to = "M2", .length_m = 10, .diameter_m = 0.6});
  b.add_pipe({.name = "P2", .from = "M2", .to = "M3", .length_m = 10, .diameter_m = 0.6});
  Diagnostics d1, d2;
  Result<SewerMap> streamed = std::move(b).build(d1);
  Result<SewerMap> whole = three_manholes().build(d2);
  ASSERT_TRUE(streamed.has_value() && whole.has_value());
  EXPECT_EQ(*streamed, *whole);
  EXPECT_EQ(d1.all(), d2.all());
}

TEST(MapBuilder, BuildsAConsistentNetworkWithSlotsAsAdjacency) {
  Diagnostics d;
  Result<SewerMap> map = three_manholes().build(d);
  ASSERT_TRUE(map.has_value()) << map.error();
  EXPECT_EQ(d.error_count(), 0U);
  EXPECT_EQ(d.warning_count(), 0U);
  const ManholeId m2 = *map->find_manhole("M2");
  ASSERT_EQ(map->slots(m2).size(), 2U);
  EXPECT_EQ(map->pipe(map->slots(m2)[1].pipe).name, "P2");
  const PipeId p2 = *map->find_pipe("P2");
  EXPECT_EQ(map->pipe(p2).ends[0].manhole, m2);
  EXPECT_EQ(map->pipe(p2).ends[0].slot, SlotIndex{1});
  EXPECT_EQ(map->pipe(p2).ends[1].manhole, map->find_manhole("M3"));
  EXPECT_FALSE(map->find_manhole("M9").has_value());
}

TEST(MapBuilder, PassageGeometryFollowsFromSlots) {
  Diagnostics d;
  Result<SewerMap> map = three_manholes().build(d);
  ASSERT_TRUE(map.has_value());
  const ManholeId m2 = *map->find_manhole("M2");
  EXPECT_DOUBLE_EQ(passage_turn_deg(*map, m2, SlotIndex{0}, SlotIndex{1}), 0.0);
  EXPECT_DOUBLE_EQ(passage_step_m(*map, m2, SlotIndex{0}, SlotIndex{1}), 0.1);
  EXPECT_DOUBLE_EQ(passage_step_m(*map, m2, SlotIndex{1}, SlotIndex{0}), -0.1);
}

TEST(MapBuilder, ReportsEveryProblemNamingTheObject) {
  MapBuilder b = three_manholes();
  b.add_pipe({.name = "P1", .from = "M1", .to = "M2", .length_m = 5, .diameter_m = 0.6});
  b.add_pipe({.name = "P7", .from = "M1", .to = "M42", .length_m = -1, .diameter_m = 0.6});
  b.add_manhole({.name = "M4", .diameter_m = 1.0, .slots = {{.pipe = "P99"}}});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidMap);
  const std::string& msg = map.error().message;
  EXPECT_THAT(msg, HasSubstr("duplicate pipe name 'P1'"));
  EXPECT_THAT(msg, HasSubstr("pipe P7: length must be a positive number of metres, got -1"));
  EXPECT_THAT(msg, HasSubstr("pipe P7: to names unknown manhole 'M42'"));
  EXPECT_THAT(msg, HasSubstr("manhole M4 slot 1 names unknown pipe 'P99'"));
  EXPECT_THAT(msg, HasSubstr("pipe P7 ends in manhole M1, but M1 has no slot for it"));
}

TEST(MapBuilder, RejectsASlotInAManholeThePipeDoesNotReach) {
  MapBuilder b = three_manholes();
  b.add_manhole({.name = "M5", .diameter_m = 1.0, .slots = {{.pipe = "P1"}}});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_FALSE(map.has_value());
  EXPECT_THAT(map.error().message,
              HasSubstr("manhole M5 slot 1 names pipe P1, but P1 joins manhole M1 and manhole M2"));
}

TEST(MapBuilder, WarnsAboutDisconnectedParts) {
  MapBuilder b = three_manholes();
  b.add_manhole({.name = "M8", .diameter_m = 1.0, .slots = {{.pipe = "P8"}}});
  b.add_manhole({.name = "M9", .diameter_m = 1.0, .slots = {{.pipe = "P8"}}});
  b.add_pipe({.name = "P8", .from = "M8", .to = "M9", .length_m = 5, .diameter_m = 0.4});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value());
  ASSERT_EQ(d.warning_count(), 1U);
  EXPECT_THAT(d.all()[0].message, HasSubstr("2 disconnected parts (sizes 3 2 manholes)"));
}

// Parts are numbered in the order of their first manhole, whatever order the pipes join them in:
// M0..M7 with the part {2, 5, 6, 7} joined from its far end (7-5, 2-7, 6-2) and a blind pipe.
TEST(MapBuilder, NumbersDisconnectedPartsByTheirFirstManhole) {
  const std::vector<std::pair<int, int>> pipes{{5, 7}, {2, 7}, {1, 4}, {6, 2}, {0, 3}, {3, -1}};
  MapBuilder b("parts");
  for (int m = 0; m < 8; ++m) {
    std::vector<SlotRecord> slots;
    for (std::size_t p = 0; p < pipes.size(); ++p) {
      if (pipes[p].first == m || pipes[p].second == m) {
        slots.push_back({.pipe = "P" + std::to_string(p)});
      }
    }
    b.add_manhole({.name = "M" + std::to_string(m),
                   .position = {10.0 * m, 0, 0},
                   .diameter_m = 1.0,
                   .slots = slots});
  }
  for (std::size_t p = 0; p < pipes.size(); ++p) {
    PipeRecord pipe{.name = "P" + std::to_string(p),
                    .from = "M" + std::to_string(pipes[p].first),
                    .length_m = 5,
                    .diameter_m = 0.4};
    if (pipes[p].second >= 0) pipe.to = "M" + std::to_string(pipes[p].second);
    b.add_pipe(pipe);
  }
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value()) << map.error().message;
  const Components parts = connected_components(*map);
  EXPECT_EQ(parts.count, 3U);
  EXPECT_EQ(parts.component_of, (std::vector<std::uint32_t>{0, 1, 2, 0, 1, 2, 2, 2}));
  EXPECT_EQ(parts.sizes, (std::vector<std::uint32_t>{2, 2, 4}));
  ASSERT_EQ(d.warning_count(), 1U);
  EXPECT_THAT(d.all()[0].message, HasSubstr("3 disconnected parts (sizes 4 2 2 manholes)"));
}

// Names are sorted by their first 8 bytes first (map_builder.cc): names that share them, or are
// prefixes of each other, are still found, and a repeated long name is still reported.
TEST(MapBuilder, FindsNamesThatShareTheirFirstEightBytes) {
  const std::vector<std::string> names{"Schacht-0012", "Schacht-001", "Schacht",
                                       "Schacht-0002", "Sch",         "Schacht-00120"};
  MapBuilder b("prefixes");
  for (std::size_t i = 0; i < names.size(); ++i) {
    b.add_manhole({.name = names[i], .diameter_m = 1.0, .exit = i == 0, .slots = {}});
  }
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value()) << map.error();
  for (std::size_t i = 0; i < names.size(); ++i) {
    ASSERT_EQ(map->find_manhole(names[i]), ManholeId{static_cast<std::uint32_t>(i)}) << names[i];
  }
  EXPECT_FALSE(map->find_manhole("Schacht-00").has_value());

  MapBuilder twice("twice");
  for (const char* name : {"Schacht-0012", "Schacht-0013", "Schacht-0012"}) {
    twice.add_manhole({.name = name, .diameter_m = 1.0, .slots = {}});
  }
  Diagnostics d2;
  EXPECT_FALSE(std::move(twice).build(d2).has_value());
  ASSERT_EQ(d2.error_count(), 1U);
  EXPECT_THAT(d2.all()[0].message, HasSubstr("duplicate manhole name 'Schacht-0012'"));
}

TEST(MapBuilder, AcceptsBlindPipeEnds) {
  MapBuilder b = three_manholes();
  b.add_manhole({.name = "M6", .diameter_m = 1.0, .slots = {{.pipe = "S1"}}});
  b.add_pipe({.name = "S1", .from = "M6", .length_m = 2, .diameter_m = 0.3});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value()) << map.error();
  EXPECT_FALSE(map->pipe(*map->find_pipe("S1")).ends[1].manhole.has_value());
}

// Issue 30: a manhole's passages are the pairs of its slots, so a manhole with 10,000 slots made
// every per-manhole listing 10^8 long. Beyond kMaxSlotsPerManhole it is an error naming it.
TEST(MapBuilder, RefusesAManholeWithMoreSlotsThanAnyRealOne) {
  auto hub = [](std::size_t n) {
    MapBuilder b("hub");
    ManholeRecord centre{.name = "HUB", .diameter_m = 1.0};
    for (std::size_t i = 0; i < n; ++i) {
      centre.slots.push_back(
          {.pipe = "P" + std::to_string(i),
           .azimuth_deg = 360.0 * static_cast<double>(i) / static_cast<double>(n)});
    }
    b.add_manhole(std::move(centre));
    for (std::size_t i = 0; i < n; ++i) {
      const std::string name = "M" + std::to_string(i);
      b.add_manhole({.name = name,
                     .position = {20, static_cast<double>(i), 0},
                     .diameter_m = 1.0,
                     .exit = true,
                     .slots = {{.pipe = "P" + std::to_string(i), .azimuth_deg = 180}}});
      b.add_pipe({.name = "P" + std::to_string(i),
                  .from = "HUB",
                  .to = name,
                  .length_m = 20,
                  .diameter_m = 0.6});
    }
    return b;
  };
  Diagnostics ok;
  EXPECT_TRUE(hub(kMaxSlotsPerManhole).build(ok).has_value());
  Diagnostics d;
  Result<SewerMap> map = hub(kMaxSlotsPerManhole + 1).build(d);
  ASSERT_FALSE(map.has_value());
  ASSERT_EQ(d.error_count(), 1U);
  EXPECT_THAT(d.all().front().message,
              HasSubstr("manhole HUB: 101 pipe ends (slots); a manhole has at most 100"));
}

TEST(MapBuilder, AnEmptyNetworkIsAWarning) {
  Diagnostics d;
  Result<SewerMap> map = MapBuilder("nothing").build(d);
  ASSERT_TRUE(map.has_value());
  ASSERT_EQ(d.warning_count(), 1U);
  EXPECT_THAT(d.all().front().message, HasSubstr("the network is empty: no manholes and no pipes"));
}

}  // namespace
}  // namespace sewerplan
