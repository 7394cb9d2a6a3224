// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_measurements.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "support/small_map.h"

namespace sewerplan {
namespace {

using testing::SmallMap;
using Kind = Discrepancy::Kind;

// A cross at M0 (slots: P1 east, P2 north, P3 west, P4 south, each 10 m), with point X1 in P1.
SewerMap cross(const std::string& name = "cross") {
  SmallMap m;
  m.manhole("M0", 0, 0, true).manhole("E", 10, 0).manhole("N", 0, 10).manhole("W", -10, 0);
  m.manhole("S", 0, -10);
  m.pipe("P1", "M0", "E").pipe("P2", "M0", "N").pipe("P3", "M0", "W").pipe("P4", "M0", "S");
  m.point("X1", "P1", 5);
  SewerMap map = m.build();
  if (name == "cross") return map;
  // The same network under another name, with one slot moved: another map.
  return SmallMap()
      .manhole("M0", 0, 0, true)
      .manhole("E", 10, 1)
      .manhole("N", 0, 10)
      .pipe("P1", "M0", "E")
      .pipe("P2", "M0", "N")
      .build();
}

MeasurementSource source(const std::string& mission) {
  return {.robot = "makro", .mission = mission, .date = "2026-12-06T07:00:00Z"};
}

ManholeId id(const SewerMap& map, const char* name) { return *map.find_manhole(name); }
PipeId pipe(const SewerMap& map, const char* name) { return *map.find_pipe(name); }

std::vector<Kind> kinds(const std::vector<FoundDiscrepancy>& found) {
  std::vector<Kind> out;
  for (const FoundDiscrepancy& f : found) out.push_back(f.discrepancy.kind);
  return out;
}

// Arrivals in M0 through every slot but `skip`, each seeing what the map predicts, then changed.
template <class Change>
void arrivals(MapMeasurements& m, const SewerMap& map, Change change, int skip = -1) {
  const ManholeId m0 = id(map, "M0");
  for (std::uint16_t a = 0; a < 4; ++a) {
    if (a == skip) continue;
    ManholeSignature seen = expected_signature(map, m0, SlotIndex{a});
    change(SlotIndex{a}, seen);
    add_observation(m, m0, SlotIndex{a}, seen, 0);
  }
}

// The sighting `s` from arrival `a` in M0 without the mouth of map slot `gone`.
void without_slot(const SewerMap& map, SlotIndex a, ManholeSignature& s, SlotIndex gone) {
  const auto order = signature_slot_order(map, id(map, "M0"), a);
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (order[i] == gone) s.slots.erase(s.slots.begin() + static_cast<long>(i));
  }
}

// The sighting `s` from arrival `a` in M0 with a mouth the map lacks at `azimuth_deg`.
void with_lateral(const SewerMap& map, SlotIndex a, ManholeSignature& s, double azimuth_deg) {
  const double rel = std::fmod(azimuth_deg - map.slot(id(map, "M0"), a).azimuth_deg + 360, 360);
  const auto at =
      std::upper_bound(s.slots.begin() + 1, s.slots.end(), rel,
                       [](double r, const SlotSighting& x) { return r < x.relative_deg; });
  s.slots.insert(at, SlotSighting{rel, 0, 0.2});
}

TEST(MapMeasurements, MergeOfTwoMissionsHasLessUncertainty) {
  const SewerMap map = cross();
  MapMeasurements a = measurements_of(map, source("one"));
  MapMeasurements b = measurements_of(map, source("two"));
  add_length(a, pipe(map, "P1"), 10.2, 0.04, 0);
  add_length(b, pipe(map, "P1"), 10.0, 0.04, 0);
  add_length(b, pipe(map, "P2"), 9.0, 0.09, 0);
  add_position(a, id(map, "E"), 10.2, 0, 0.04, 0);
  add_position(b, id(map, "E"), 10.0, 0, 0.04, 0);
  const Result<MapMeasurements> merged = merge(a, b);
  ASSERT_TRUE(merged.has_value()) << merged.error().message;
  ASSERT_EQ(merged->sources.size(), 2u);
  EXPECT_EQ(merged->sources[1].mission, "two");
  ASSERT_EQ(merged->pipes.size(), 2u);
  const PipeMeasurement& p1 = merged->pipes[0];
  EXPECT_NEAR(p1.length_m.mean, 10.1, 1e-12);
  EXPECT_NEAR(p1.length_m.variance, 0.02, 1e-12);  // half of each
  EXPECT_EQ(p1.length_m.count, 2u);
  EXPECT_EQ(p1.sources, (SourceList{0, 1}));
  EXPECT_EQ(merged->pipes[1].sources, (SourceList{1}));  // b's source 0 is the merged 1
  ASSERT_EQ(merged->manholes.size(), 1u);
  EXPECT_NEAR(merged->manholes[0].position->x_m.variance, 0.02, 1e-12);
  // Unequal variances: the better measurement weighs more.
  EXPECT_NEAR(pool({10, 0.01, 1}, {11, 0.04, 1}).mean, 10.2, 1e-12);
}

TEST(MapMeasurements, MergeRefusesMeasurementsOfAnotherMap) {
  const SewerMap map = cross();
  const SewerMap other = cross("other");
  const Result<MapMeasurements> merged =
      merge(measurements_of(map, source("one")), measurements_of(other, source("two")));
  ASSERT_FALSE(merged.has_value());
  EXPECT_EQ(merged.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(merged.error().message.find("different maps"), std::string::npos)
      << merged.error().message;
}

TEST(MapMeasurements, NoDiscrepancyForNoiseWithinThresholds) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  // Lengths off by one sigma or less (0.3 m); directions by 4° (half the noise); sizes by 1 cm.
  const double off[] = {0.3, -0.2, 0.1, -0.3};
  for (int p = 0; p < 4; ++p)
    add_length(m, PipeId{static_cast<std::uint32_t>(p)}, 10 + off[p], 0.09, 0);
  arrivals(m, map, [](SlotIndex a, ManholeSignature& s) {
    for (std::size_t i = 1; i < s.slots.size(); ++i) {
      s.slots[i].relative_deg += (i + a.value()) % 2 == 0 ? 4 : -4;
      s.slots[i].diameter_m -= 0.01;
    }
  });
  EXPECT_TRUE(discrepancies(m, map).empty());
}

TEST(MapMeasurements, ALengthOffBeyondItsSigmaIsFound) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  add_length(m, pipe(map, "P2"), 12.0, 0.09, 0);
  add_length(m, pipe(map, "P3"), 10.4, 0.09, 0);  // 1.3 sigma: noise
  const auto found = discrepancies(m, map);
  ASSERT_EQ(found.size(), 1u);
  const Discrepancy& d = found[0].discrepancy;
  EXPECT_EQ(d.kind, Kind::kLengthOff);
  EXPECT_EQ(d.pipe, pipe(map, "P2"));
  EXPECT_DOUBLE_EQ(d.value, 12.0);
  EXPECT_DOUBLE_EQ(d.map_value, 10.0);
  EXPECT_NEAR(d.sigma, 0.3, 1e-12);
  EXPECT_EQ(found[0].sources, (SourceList{0}));
  // Beyond k sigma but under the floor (2 % of the length): a well-measured pipe is not nagged.
  MapMeasurements precise = measurements_of(map, source("one"));
  add_length(precise, pipe(map, "P2"), 10.1, 1e-4, 0);
  EXPECT_TRUE(discrepancies(precise, map).empty());
}

TEST(MapMeasurements, ASlotDirectionOffIsFoundOnItsOwnSlot) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  // P2 (north, slot 2) really leaves at 115°: seen 25° further counter-clockwise from every other
  // arrival slot.
  arrivals(
      m, map,
      [&](SlotIndex a, ManholeSignature& s) {
        const auto order = signature_slot_order(map, id(map, "M0"), a);
        for (std::size_t i = 1; i < order.size(); ++i) {
          if (order[i] == SlotIndex{1}) s.slots[i].relative_deg += 25;
        }
      },
      /*skip=*/1);
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kDirectionOff});
  EXPECT_EQ(found[0].discrepancy.slot, SlotIndex{1});
  EXPECT_NEAR(found[0].discrepancy.value, 115, 1e-6);
  EXPECT_DOUBLE_EQ(found[0].discrepancy.map_value, 90);
}

// Turns from `from` to `to` in M0, `count` of them, the joints measuring `off` degrees more than
// the map's angle between the two slots, alternately 0.5 degrees either side (noise).
void turns(MapMeasurements& m, const SewerMap& map, std::uint16_t from, std::uint16_t to,
           double off, int count) {
  const ManholeId m0 = id(map, "M0");
  const double mapped = std::fmod(
      map.slot(m0, SlotIndex{to}).azimuth_deg - map.slot(m0, SlotIndex{from}).azimuth_deg + 360.0,
      360.0);
  for (int i = 0; i < count; ++i) {
    add_turn(m, m0,
             {.from = SlotIndex{from},
              .to = SlotIndex{to},
              .relative_deg = std::fmod(mapped + off + (i % 2 == 0 ? 0.5 : -0.5) + 360.0, 360.0),
              .sigma_deg = 1.0,
              .source = 0});
  }
}

// A slot a few degrees off is lost in the sightings' 8 degrees of noise, arrival after arrival;
// the turns through it, which the joints measure to a degree, find it (issue 29: slot directions
// 5 to 20 degrees off were found 13 % of the time from sightings alone).
TEST(MapMeasurements, TurnsFindASlotAFewDegreesOff) {
  const SewerMap map = cross();
  // P2 (north, slot 2) really leaves at 97 degrees: every sighting of it 7 degrees further, and
  // the other mouths seen with 6 degrees of noise.
  const auto seen_off = [&](SlotIndex a, ManholeSignature& s) {
    const auto order = signature_slot_order(map, id(map, "M0"), a);
    for (std::size_t i = 1; i < order.size(); ++i) {
      s.slots[i].relative_deg += (i + a.value()) % 2 == 0 ? 6 : -6;
      if (order[i] == SlotIndex{1}) s.slots[i].relative_deg += 7;
    }
  };
  MapMeasurements sighted = measurements_of(map, source("one"));
  arrivals(sighted, map, seen_off, /*skip=*/1);
  arrivals(sighted, map, seen_off, /*skip=*/1);
  EXPECT_TRUE(discrepancies(sighted, map).empty());

  MapMeasurements turned = sighted;
  turns(turned, map, 0, 1, 7, 2);  // from P1 (east) into P2 (north): 97 degrees, not 90
  turns(turned, map, 2, 1, 7, 2);  // from P3 (west) into P2: 277, not 270
  turns(turned, map, 2, 0, 0, 1);  // from P3 into P1: as mapped
  const auto found = discrepancies(turned, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kDirectionOff});
  EXPECT_EQ(found[0].discrepancy.manhole, id(map, "M0"));
  EXPECT_EQ(found[0].discrepancy.slot, SlotIndex{1});
  EXPECT_NEAR(found[0].discrepancy.value, 97, 0.5);
  EXPECT_LT(found[0].discrepancy.sigma, 1.0);
  EXPECT_EQ(found[0].sources, (SourceList{0}));
}

// Two slots whose angle differs from the map's: either could be off (the robot has no compass).
// The report says so, naming both (issue 29: every manhole of two mouths, a fifth of the slot
// directions seeded off on AIS, was never reported), and a corrected map applies neither. A turn
// far off the map's angle (beyond the 30 degrees that pair mouths) is not between these two
// mouths: the controller had the robot in another manhole; it is left out.
TEST(MapMeasurements, AnAngleOffBetweenTwoSlotsAloneIsReportedOnBoth) {
  const SewerMap map = SmallMap()
                           .manhole("M1", 0, 0, true)
                           .manhole("M0", 10, 0)
                           .manhole("M3", 20, 0)
                           .pipe("P1", "M1", "M0")
                           .pipe("P2", "M0", "M3")
                           .build();
  MapMeasurements m = measurements_of(map, source("one"));
  turns(m, map, 0, 1, 15, 6);
  turns(m, map, 1, 0, -15, 6);
  m.discrepancies = discrepancies(m, map);
  ASSERT_EQ(kinds(m.discrepancies), std::vector<Kind>{Kind::kDirectionOff});
  const Discrepancy& d = m.discrepancies[0].discrepancy;
  EXPECT_EQ(d.manhole, id(map, "M0"));
  EXPECT_EQ(d.slot, SlotIndex{0});
  EXPECT_EQ(d.or_slot, SlotIndex{1});
  // Slot 1 (P1, west: 180 degrees) turned 15 the other way, or slot 2 (P2, east) 15 this way.
  EXPECT_NEAR(d.value, 165, 0.5);
  EXPECT_DOUBLE_EQ(d.map_value, 180);
  EXPECT_EQ(describe(d, map),
            "M0 slot 1: leaves at 165°, the map says 180°; or slot 2 leaves at 15°, the map says "
            "0° (the angle between the two was measured, not which is off)");
  // Either slot seeded off is the same difference; the manhole's other slots, or another
  // manhole, are not.
  const auto seeded = [&](const char* manhole, std::uint16_t slot) {
    return Discrepancy{
        .kind = Kind::kDirectionOff, .manhole = id(map, manhole), .slot = SlotIndex{slot}};
  };
  EXPECT_TRUE(same_difference(d, seeded("M0", 0)));
  EXPECT_TRUE(same_difference(seeded("M0", 1), d));
  EXPECT_FALSE(same_difference(d, seeded("M1", 0)));
  Discrepancy three = d;
  three.slot = SlotIndex{2};
  three.or_slot = SlotIndex{3};
  EXPECT_FALSE(same_difference(d, three));

  const Result<CorrectedMap> fixed = corrected_map(map, m);
  ASSERT_TRUE(fixed.has_value()) << fixed.error().message;
  ASSERT_EQ(fixed->applied.size(), 1u);
  EXPECT_FALSE(fixed->applied[0].second);
  for (std::uint16_t s = 0; s < 2; ++s) {
    EXPECT_DOUBLE_EQ(fixed->map.slot(id(fixed->map, "M0"), SlotIndex{s}).azimuth_deg,
                     map.slot(id(map, "M0"), SlotIndex{s}).azimuth_deg);
  }

  const SewerMap four = cross();
  MapMeasurements elsewhere = measurements_of(four, source("one"));
  turns(elsewhere, four, 0, 1, 90, 3);  // "97" was 180: another manhole
  turns(elsewhere, four, 0, 2, 0, 3);
  EXPECT_TRUE(discrepancies(elsewhere, four).empty());
}

// Of four slots, the turns tie two of them only to each other (from P1 into P2, both ways), and
// nothing places the others: the angle between the two is measured, which one is off is not.
TEST(MapMeasurements, TwoSlotsTheTurnsCannotTellApartAreReportedTogether) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  turns(m, map, 0, 1, 12, 4);
  turns(m, map, 1, 0, -12, 4);
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kDirectionOff});
  EXPECT_EQ(found[0].discrepancy.slot, SlotIndex{0});
  EXPECT_EQ(found[0].discrepancy.or_slot, SlotIndex{1});

  // A third slot tied to the first two by turns as mapped: slot 2 (P2) is the one off.
  turns(m, map, 2, 0, 0, 4);
  turns(m, map, 2, 1, 12, 4);
  const auto pinned = discrepancies(m, map);
  ASSERT_EQ(kinds(pinned), std::vector<Kind>{Kind::kDirectionOff});
  EXPECT_EQ(pinned[0].discrepancy.slot, SlotIndex{1});
  EXPECT_FALSE(pinned[0].discrepancy.or_slot.has_value());
}

TEST(MapMeasurements, MergeJoinsTheTurns) {
  const SewerMap map = cross();
  MapMeasurements a = measurements_of(map, source("one"));
  MapMeasurements b = measurements_of(map, source("two"));
  turns(a, map, 0, 1, 7, 1);
  turns(b, map, 2, 1, -7, 2);
  const Result<MapMeasurements> merged = merge(a, b);
  ASSERT_TRUE(merged.has_value()) << merged.error().message;
  ASSERT_EQ(merged->manholes.size(), 1u);
  ASSERT_EQ(merged->manholes[0].turns.size(), 3u);
  EXPECT_EQ(merged->manholes[0].turns[0].source, 0u);
  EXPECT_EQ(merged->manholes[0].turns[2].source, 1u);  // b's source 0 is the merged 1
  EXPECT_EQ(merged->manholes[0].sources, (SourceList{0, 1}));
}

TEST(MapMeasurements, ASmallerPipeIsFound) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  arrivals(m, map, [&](SlotIndex a, ManholeSignature& s) {
    const auto order = signature_slot_order(map, id(map, "M0"), a);
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (order[i] == SlotIndex{3}) s.slots[i].diameter_m = 0.35;
    }
  });
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kDiameterSmaller});
  EXPECT_EQ(found[0].discrepancy.pipe, pipe(map, "P4"));
  EXPECT_NEAR(found[0].discrepancy.value, 0.35, 1e-12);
}

// A 0.10 m house connection 6 degrees beside a 0.40 m sewer (as in the official ISYBAU sample):
// seen in either order, depending on the noise. Seen swapped, each mouth is paired with its own
// sighting by size, so neither pipe is reported smaller and no direction is off.
TEST(MapMeasurements, TwoMouthsSideBySideSeenSwappedArePairedBySize) {
  const SewerMap map = SmallMap()
                           .manhole("M0", 0, 0, true)
                           .manhole("E", 20, 0)
                           .manhole("H", 20, 2.1)
                           .manhole("W", -20, 0)
                           .pipe("SEWER", "M0", "E", 0.40)
                           .pipe("HOUSE", "H", "M0", 0.10)
                           .pipe("IN", "W", "M0", 0.40)
                           .build();
  const ManholeId m0 = id(map, "M0");
  MapMeasurements m = measurements_of(map, source("one"));
  const SlotIndex in = map.pipe(pipe(map, "IN")).ends[1].slot;
  for (int pass = 0; pass < 3; ++pass) {
    ManholeSignature seen = expected_signature(map, m0, in);
    ASSERT_EQ(seen.slots.size(), 3U);
    // The two mouths east, 6 degrees apart, seen the other way round: their sizes trade places.
    std::swap(seen.slots[1].diameter_m, seen.slots[2].diameter_m);
    add_observation(m, m0, in, seen, 0);
  }
  EXPECT_TRUE(discrepancies(m, map).empty());

  // A sewer truly smaller beside the connection is still found.
  MapMeasurements smaller = measurements_of(map, source("two"));
  const auto order = signature_slot_order(map, m0, in);
  for (int pass = 0; pass < 3; ++pass) {
    ManholeSignature seen = expected_signature(map, m0, in);
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (map.slot(m0, order[i]).pipe == pipe(map, "SEWER")) seen.slots[i].diameter_m = 0.30;
    }
    std::swap(seen.slots[1], seen.slots[2]);
    std::swap(seen.slots[1].relative_deg, seen.slots[2].relative_deg);
    add_observation(smaller, m0, in, seen, 0);
  }
  const auto found = discrepancies(smaller, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kDiameterSmaller});
  EXPECT_EQ(found[0].discrepancy.pipe, pipe(map, "SEWER"));
  EXPECT_NEAR(found[0].discrepancy.value, 0.30, 1e-9);
}

TEST(MapMeasurements, AMouthTheMapLacksIsAnUnmappedLateral) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  // A lateral at 45° (between east and north), seen from every arrival.
  arrivals(m, map, [&](SlotIndex a, ManholeSignature& s) { with_lateral(map, a, s, 45); });
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kUnmappedLateral});
  EXPECT_EQ(found[0].discrepancy.manhole, id(map, "M0"));
  EXPECT_NEAR(found[0].discrepancy.value, 45, 1e-6);
}

TEST(MapMeasurements, AMappedSlotNeverSeenIsAMissingLateral) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  // The south mouth (slot 4) is not there: never seen from the three other arrivals.
  arrivals(
      m, map, [&](SlotIndex a, ManholeSignature& s) { without_slot(map, a, s, SlotIndex{3}); },
      /*skip=*/3);
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kMissingLateral});
  EXPECT_EQ(found[0].discrepancy.slot, SlotIndex{3});
}

// A slot off by more than the alignment pairs (north seen 40 degrees towards the west from every
// arrival, beyond its 30) is that slot, off: not a lateral the map lacks beside a mapped mouth
// never seen (11 of 27 false reports on AIS, 200 runs of the realistic world).
TEST(MapMeasurements, AMouthSeenFarOffItsMappedDirectionIsThatMouthOff) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  const ManholeId m0 = id(map, "M0");
  arrivals(
      m, map,
      [&](SlotIndex a, ManholeSignature& s) {
        const auto order = signature_slot_order(map, m0, a);
        std::vector<SlotSighting> sorted(s.slots.begin() + 1, s.slots.end());
        for (std::size_t i = 1; i < order.size(); ++i) {
          if (order[i] == SlotIndex{1}) sorted[i - 1].relative_deg += 40;
        }
        std::sort(sorted.begin(), sorted.end(), [](const SlotSighting& x, const SlotSighting& y) {
          return x.relative_deg < y.relative_deg;
        });
        std::copy(sorted.begin(), sorted.end(), s.slots.begin() + 1);
      },
      /*skip=*/1);
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kDirectionOff});
  EXPECT_EQ(found[0].discrepancy.slot, SlotIndex{1});
  EXPECT_NEAR(found[0].discrepancy.value, 130, 1e-6);
}

// Farther than that from every mapped mouth not seen, a mouth is a lateral the map lacks, and the
// mapped one a missing lateral (the south mouth gone, a lateral at 200 degrees: 70 degrees apart).
TEST(MapMeasurements, AMouthFarFromEveryUnseenOneIsStillALateral) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  arrivals(
      m, map,
      [&](SlotIndex a, ManholeSignature& s) {
        without_slot(map, a, s, SlotIndex{3});
        with_lateral(map, a, s, 200);
      },
      /*skip=*/3);
  const auto found = discrepancies(m, map);
  EXPECT_EQ(kinds(found), (std::vector<Kind>{Kind::kUnmappedLateral, Kind::kMissingLateral}));
}

TEST(MapMeasurements, AManholeSightedInAPipeIsAnUnmappedJunction) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  ManholeSignature three = expected_signature(map, id(map, "M0"), SlotIndex{0});
  three.slots.pop_back();
  m.junctions.push_back({pipe(map, "P1"), 4.0, 0.2, three, 0});
  m.junctions.push_back({pipe(map, "P1"), 4.4, 0.2, three, 0});  // the same one, seen again
  const auto found = discrepancies(m, map);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kUnmappedJunction});
  EXPECT_NEAR(found[0].discrepancy.offset_m, 4.2, 1e-12);
  EXPECT_DOUBLE_EQ(found[0].discrepancy.value, 3);
}

TEST(MapMeasurements, PositionsAreReportedOnlyWhenAsked) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  add_position(m, id(map, "E"), 14, 0, 0.25, 0);
  EXPECT_TRUE(discrepancies(m, map).empty());
  const auto found = discrepancies(m, map, {.report_positions = true});
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::kPositionOff});
  EXPECT_NEAR(found[0].discrepancy.value, 4, 1e-12);
}

// A driven pipe's corrected length weighs the measurement against the map's (LengthPrior): within
// the measurement's noise of the map it stays near the map's length, far off it is the measured
// one, and with a precise measurement it is the measurement wherever it lies.
TEST(MapMeasurements, ACorrectedLengthWeighsTheMeasurementAgainstTheMap) {
  const PooledValue noisy_near{.mean = 41.0, .variance = std::pow(0.03 * 40, 2), .count = 1};
  EXPECT_NEAR(corrected_length_m(40.0, noisy_near), 40.0, 0.2);
  const PooledValue noisy_far{.mean = 46.0, .variance = std::pow(0.03 * 40, 2), .count = 1};
  EXPECT_NEAR(corrected_length_m(40.0, noisy_far), 46.0, 0.05);
  const PooledValue precise{.mean = 41.0, .variance = 1e-6, .count = 4};
  EXPECT_NEAR(corrected_length_m(40.0, precise), 41.0, 1e-3);
  // Between, it moves monotonically from the map's length to the measurement's.
  double last = 0;
  for (double measured = 40.0; measured <= 48.0; measured += 0.25) {
    const double c = corrected_length_m(40.0, {.mean = measured, .variance = 1.44, .count = 1});
    EXPECT_GE(c, last - 1e-9) << measured;
    EXPECT_GE(c, 40.0 - 1e-9);
    EXPECT_LE(c, measured + 1e-9);
    last = c;
  }
  // An operator who trusts no length of the map gets the measurements.
  EXPECT_NEAR(corrected_length_m(40.0, noisy_near, {.right_share = 0}), 41.0, 1e-12);
  // A prior out of range is refused by corrected_map, naming it.
  const SewerMap map = cross();
  const Result<CorrectedMap> refused =
      corrected_map(map, measurements_of(map, source("one")), {.right_share = 1.5});
  ASSERT_FALSE(refused.has_value());
  EXPECT_NE(refused.error().message.find("right_share"), std::string::npos);
}

TEST(MapMeasurements, TheCorrectedMapCarriesLengthsAndDirections) {
  const SewerMap map = cross();
  MapMeasurements m = measurements_of(map, source("one"));
  add_length(m, pipe(map, "P1"), 12.0, 0.09, 0);
  add_length(m, pipe(map, "P3"), 10.1, 0.09, 0);  // measured, not a discrepancy
  m.discrepancies = discrepancies(m, map);
  m.discrepancies.push_back({{.kind = Kind::kDirectionOff,
                              .manhole = id(map, "M0"),
                              .slot = SlotIndex{1},
                              .map_value = 90,
                              .value = 100},
                             {0}});
  m.discrepancies.push_back(
      {{.kind = Kind::kUnmappedLateral, .manhole = id(map, "M0"), .value = 45}, {0}});
  const Result<CorrectedMap> fixed = corrected_map(map, m);
  ASSERT_TRUE(fixed.has_value()) << fixed.error().message;
  EXPECT_NEAR(fixed->map.pipe(pipe(map, "P1")).length_m, 12.0, 1e-6);  // 20 % off: measured
  // 1 % off, measured with 3 % noise: mostly the map's length.
  EXPECT_NEAR(fixed->map.pipe(pipe(map, "P3")).length_m, 10.0, 0.02);
  EXPECT_DOUBLE_EQ(fixed->map.pipe(pipe(map, "P2")).length_m, 10.0);
  EXPECT_DOUBLE_EQ(fixed->map.slot(id(map, "M0"), SlotIndex{1}).azimuth_deg, 100);
  EXPECT_NEAR(fixed->map.point(*map.find_point("X1")).offset_m, 6.0, 1e-6);  // moved with P1
  ASSERT_EQ(fixed->applied.size(), 3u);
  EXPECT_TRUE(fixed->applied[0].second);   // length
  EXPECT_TRUE(fixed->applied[1].second);   // direction
  EXPECT_FALSE(fixed->applied[2].second);  // a lateral: listed, not added
  // Nothing measured: the same map.
  const Result<CorrectedMap> same = corrected_map(map, measurements_of(map, source("one")));
  ASSERT_TRUE(same.has_value());
  EXPECT_EQ(same->map, map);
  // Measurements of another map are refused.
  const Result<CorrectedMap> wrong = corrected_map(cross("other"), m);
  ASSERT_FALSE(wrong.has_value());
  EXPECT_NE(wrong.error().message.find("not of map"), std::string::npos);
}

}  // namespace
}  // namespace sewerplan
