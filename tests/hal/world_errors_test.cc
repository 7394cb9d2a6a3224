// SPDX-License-Identifier: MIT
#include "sewerplan/hal/world_errors.h"

#include <cmath>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"

#include "support/ais_testbed.h"

namespace sewerplan::hal {
namespace {

using ::testing::HasSubstr;

const SewerMap& ais() {
  static const SewerMap map = testing::load_ais_testbed().map;
  return map;
}

const SewerMap& thousand() {
  static const SewerMap map = *generate_network(
      {.manholes = 1000, .seed = 3, .topology = Topology::kMeshed, .mesh_fraction = 0.3});
  return map;
}

std::map<Discrepancy::Kind, std::size_t> counts(const TrueWorld& truth) {
  std::map<Discrepancy::Kind, std::size_t> n;
  for (const Discrepancy& d : truth.seeded) ++n[d.kind];
  return n;
}

// Within 4 standard deviations of a binomial count of n draws at p.
void expect_rate(std::size_t count, std::size_t n, double p, const char* what) {
  const double mean = p * static_cast<double>(n);
  const double sd = std::sqrt(mean * (1 - p));
  EXPECT_NEAR(static_cast<double>(count), mean, 4 * sd + 1) << what << " over " << n;
}

TEST(WorldErrors, NoneGivesAWorldEqualToTheMap) {
  for (const SewerMap* map : {&ais(), &thousand()}) {
    const Result<TrueWorld> truth = make_true_world(*map, WorldErrorProfile{}, 7);
    ASSERT_TRUE(truth.has_value()) << truth.error().message;
    EXPECT_TRUE(truth->world == *map) << map->name();
    EXPECT_TRUE(truth->seeded.empty());
  }
}

TEST(WorldErrors, EachKindAppearsAtItsRate) {
  const SewerMap& map = thousand();
  const WorldErrorProfile profile{.length_share = 0.2,
                                  .length_max_rel = 0.2,
                                  .direction_share = 0.1,
                                  .direction_max_deg = 20,
                                  .position_share = 0.15,
                                  .position_max_m = 2,
                                  .junction_share = 0.03,
                                  .lateral_extra_share = 0.05,
                                  .lateral_missing_share = 0.2,
                                  .diameter_share = 0.1,
                                  .diameter_max_rel = 0.2,
                                  .wet_share = 0.3};
  const Result<TrueWorld> truth = make_true_world(map, profile, 11);
  ASSERT_TRUE(truth.has_value()) << truth.error().message;
  auto n = counts(*truth);
  std::size_t junction_manholes = 0;
  for (ManholeId m : map.manhole_ids())
    if (map.slots(m).size() >= 3) ++junction_manholes;
  expect_rate(n[Discrepancy::Kind::kLengthOff], map.pipe_count(), 0.2, "lengths");
  expect_rate(n[Discrepancy::Kind::kDirectionOff], map.slot_count(), 0.1, "directions");
  expect_rate(n[Discrepancy::Kind::kPositionOff], map.manhole_count(), 0.15, "positions");
  expect_rate(n[Discrepancy::Kind::kUnmappedJunction], map.manhole_count(), 0.03, "junctions");
  expect_rate(n[Discrepancy::Kind::kUnmappedLateral], map.manhole_count(), 0.05, "laterals");
  // A missing lateral is drawn at junctions (three or more slots), and skipped when its pipe has
  // lost its other end already: a little below the rate.
  EXPECT_LE(n[Discrepancy::Kind::kMissingLateral], junction_manholes);
  expect_rate(n[Discrepancy::Kind::kMissingLateral], junction_manholes, 0.2, "missing laterals");
  expect_rate(n[Discrepancy::Kind::kDiameterSmaller], map.pipe_count(), 0.1, "diameters");
  std::size_t wet = 0;
  for (bool w : truth->wet) wet += w ? 1U : 0U;
  expect_rate(wet, truth->world.pipe_count(), 0.3, "wet pipes");
  // Magnitudes within their bounds.
  for (const Discrepancy& d : truth->seeded) {
    switch (d.kind) {
      case Discrepancy::Kind::kLengthOff: {
        const double rel = std::abs(d.value / d.map_value - 1);
        EXPECT_GE(rel, 0.05 - 1e-9);
        EXPECT_LE(rel, 0.2 + 1e-9);
        EXPECT_DOUBLE_EQ(
            truth->world.pipe(*d.pipe).length_m +
                [&] {
                  for (const PipeSplit& s : truth->splits) {
                    if (s.pipe == *d.pipe) return truth->world.pipe(s.rest).length_m;
                  }
                  return 0.0;
                }(),
            d.value)
            << describe(d, map) << " / world " << truth->world.pipe(*d.pipe).name << " "
            << truth->world.pipe(*d.pipe).length_m;
        break;
      }
      case Discrepancy::Kind::kDirectionOff: {
        double off = std::abs(d.value - d.map_value);
        off = std::min(off, 360 - off);
        EXPECT_GE(off, 5 - 1e-9);
        EXPECT_LE(off, 20 + 1e-9);
        EXPECT_DOUBLE_EQ(truth->world.slot(*d.manhole, *d.slot).azimuth_deg, d.value);
        break;
      }
      case Discrepancy::Kind::kPositionOff: {
        const Position& a = map.manhole(*d.manhole).position;
        const Position& b = truth->world.manhole(*d.manhole).position;
        EXPECT_NEAR(std::hypot(a.x_m - b.x_m, a.y_m - b.y_m), d.value, 1e-9);
        EXPECT_LE(d.value, 2 + 1e-9);
        break;
      }
      case Discrepancy::Kind::kDiameterSmaller:
        EXPECT_LT(d.value, d.map_value);
        EXPECT_GE(d.value, 0.8 * d.map_value - 1e-12);
        EXPECT_DOUBLE_EQ(truth->world.pipe(*d.pipe).diameter_m, d.value);
        break;
      case Discrepancy::Kind::kUnmappedJunction:
      case Discrepancy::Kind::kUnmappedLateral:
      case Discrepancy::Kind::kMissingLateral:
        break;
    }
  }
}

TEST(WorldErrors, KeepsEveryMapIdAndSlotIndexAndAppendsWhatOnlyTheWorldHas) {
  const SewerMap& map = thousand();
  const Result<TrueWorld> truth =
      make_true_world(map, *parse_world_errors("realistic,junctions=0.05,laterals_missing=0.3"), 5);
  ASSERT_TRUE(truth.has_value()) << truth.error().message;
  const SewerMap& world = truth->world;
  ASSERT_GT(world.manhole_count(), map.manhole_count());
  ASSERT_GT(world.pipe_count(), map.pipe_count());
  for (ManholeId m : map.manhole_ids()) {
    EXPECT_EQ(world.manhole(m).name, map.manhole(m).name);
  }
  for (PipeId p : map.pipe_ids()) EXPECT_EQ(world.pipe(p).name, map.pipe(p).name);
  for (std::size_t i = map.manhole_count(); i < world.manhole_count(); ++i) {
    EXPECT_THAT(world.manhole(ManholeId{static_cast<std::uint32_t>(i)}).name, HasSubstr("world-J"));
  }
  std::map<PipeId, PipeId> rest;
  for (const PipeSplit& s : truth->splits) rest.emplace(s.pipe, s.rest);
  std::size_t missing = 0;
  for (ManholeId m : map.manhole_ids()) {
    const auto map_slots = map.slots(m);
    const auto world_slots = world.slots(m);
    // Only the last slot is ever taken away; every slot that stays has its index.
    const bool lost_last = world_slots.size() + 1 == map_slots.size();
    missing += lost_last ? 1U : 0U;
    for (std::size_t s = 0; s < std::min(map_slots.size(), world_slots.size()); ++s) {
      const PipeId p = map_slots[s].pipe;
      const PipeId w = world_slots[s].pipe;
      // The same pipe, or the rest of the same pipe beyond an unmapped junction.
      EXPECT_TRUE(w == p || (rest.contains(p) && rest.at(p) == w))
          << map.manhole(m).name << " slot " << s;
    }
    for (std::size_t s = map_slots.size(); s < world_slots.size(); ++s) {
      EXPECT_GE(world_slots[s].pipe.index(), map.pipe_count()) << "an appended slot's new pipe";
    }
  }
  EXPECT_EQ(missing, counts(*truth)[Discrepancy::Kind::kMissingLateral]);
}

TEST(WorldErrors, IsTheSameForTheSameSeedAndDiffersForAnother) {
  const WorldErrorProfile realistic = *parse_world_errors("realistic");
  const TrueWorld a = *make_true_world(thousand(), realistic, 42);
  const TrueWorld b = *make_true_world(thousand(), realistic, 42);
  const TrueWorld c = *make_true_world(thousand(), realistic, 43);
  EXPECT_TRUE(a.world == b.world);
  EXPECT_EQ(a.seeded, b.seeded);
  EXPECT_EQ(a.wet, b.wet);
  EXPECT_FALSE(a.seeded == c.seeded);
}

TEST(WorldErrors, PlacesOnAMapPipeLandInTheWorldOnTheSplitsRest) {
  const SewerMap& map = thousand();
  const TrueWorld truth = *make_true_world(map, {.junction_share = 0.05}, 9);
  ASSERT_FALSE(truth.splits.empty());
  const PipeSplit& s = truth.splits.front();
  const double map_m = map.pipe(s.pipe).length_m;
  EXPECT_DOUBLE_EQ(truth.world.pipe(s.pipe).length_m + truth.world.pipe(s.rest).length_m, map_m);
  const WorldSpot before = world_spot(map, truth, s.pipe, s.at_m / 2);
  EXPECT_EQ(before.pipe, s.pipe);
  EXPECT_DOUBLE_EQ(before.offset_m, s.at_m / 2);
  const WorldSpot after = world_spot(map, truth, s.pipe, map_m - 1);
  EXPECT_EQ(after.pipe, s.rest);
  EXPECT_NEAR(after.offset_m, truth.world.pipe(s.rest).length_m - 1, 1e-9);
}

TEST(WorldErrorsParser, ReadsNamesKeysAndOverrides) {
  EXPECT_EQ(*parse_world_errors("none"), WorldErrorProfile{});
  const WorldErrorProfile realistic = *parse_world_errors("realistic");
  EXPECT_DOUBLE_EQ(realistic.length_share, 0.10);
  EXPECT_DOUBLE_EQ(realistic.length_max_rel, 0.20);
  EXPECT_DOUBLE_EQ(realistic.junction_share, 0.03);
  EXPECT_DOUBLE_EQ(realistic.lateral_missing_share, 0.03);
  EXPECT_DOUBLE_EQ(realistic.direction_max_deg, 20);
  EXPECT_DOUBLE_EQ(realistic.drift, 0.03);
  EXPECT_DOUBLE_EQ(realistic.missed_share, 0.05);
  WorldErrorProfile more = realistic;
  more.drift = 0.05;
  EXPECT_EQ(*parse_world_errors("realistic,drift=0.05"), more);
  const WorldErrorProfile only = *parse_world_errors("lengths=0.5,length_rel=0.1");
  EXPECT_EQ(only, (WorldErrorProfile{.length_share = 0.5, .length_max_rel = 0.1}));
  // The canonical form reads back to the same.
  EXPECT_EQ(*parse_world_errors(format_world_errors(realistic)), realistic);
}

TEST(WorldErrorsParser, NamesEveryBadItem) {
  const auto message = [](std::string_view text) {
    const Result<WorldErrorProfile> r = parse_world_errors(text);
    EXPECT_FALSE(r.has_value()) << text;
    return r.has_value() ? std::string() : r.error().message;
  };
  EXPECT_THAT(message("realism"), HasSubstr("unknown profile 'realism' (known: none, realistic)"));
  EXPECT_THAT(message("realistic,dirft=0.1"), HasSubstr("'dirft=0.1': unknown key"));
  EXPECT_THAT(message("drift=abc"), HasSubstr("'drift=abc': not a number"));
  EXPECT_THAT(message("drift="), HasSubstr("'drift=': not a number"));
  EXPECT_THAT(message("drift=0.1x"), HasSubstr("not a number"));
  EXPECT_THAT(message("lengths=1.5"), HasSubstr("'lengths=1.5': must be from 0 to 1"));
  EXPECT_THAT(message("lengths=-0.1"), HasSubstr("must be from 0"));
  EXPECT_THAT(message("length_rel=0.95"), HasSubstr("must be from 0 to 0.9"));
  EXPECT_THAT(message("drift=nan"), HasSubstr("not a number"));
  EXPECT_THAT(message("realistic,drift"), HasSubstr("'drift': no '='"));
  EXPECT_THAT(message("realistic,"), HasSubstr("ends in ','"));
  EXPECT_THAT(message("drift=0.1,"), HasSubstr("empty item"));
  EXPECT_THAT(message(""), HasSubstr("empty"));
  // make_true_world refuses a profile out of range too.
  const Result<TrueWorld> bad = make_true_world(thousand(), {.length_share = 2}, 1);
  ASSERT_FALSE(bad.has_value());
  EXPECT_THAT(bad.error().message, HasSubstr("lengths = 2"));
}

}  // namespace
}  // namespace sewerplan::hal
