// SPDX-License-Identifier: MIT
#include "sewerplan/core/manhole_signature.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "sewerplan/core/map_discrepancy.h"

#include "support/small_map.h"

namespace sewerplan {
namespace {

using testing::SmallMap;

// A cross at M0: pipes east (P1), north (P2), west (P3, 0.3 m) and south (P4, its invert 0.2 m up).
SewerMap cross() {
  return SmallMap()
      .manhole("M0", 0, 0)
      .manhole("E", 10, 0)
      .manhole("N", 0, 10)
      .manhole("W", -10, 0)
      .manhole("S", 0, -10)
      .pipe("P1", "M0", "E")
      .pipe("P2", "M0", "N")
      .pipe("P3", "M0", "W", 0.3)
      .pipe("P4", "M0", "S")
      .invert("M0", "P4", 0.2)
      .build();
}

TEST(ManholeSignature, ListsSlotsCounterClockwiseFromTheArrival) {
  const SewerMap map = cross();
  const ManholeId m0 = *map.find_manhole("M0");
  // Arriving from the west (slot 3, P3): then south (90° ccw), east (180°), north (270°).
  const ManholeSignature s = expected_signature(map, m0, SlotIndex{2});
  ASSERT_EQ(s.slots.size(), 4u);
  EXPECT_DOUBLE_EQ(s.slots[0].relative_deg, 0);
  EXPECT_DOUBLE_EQ(s.slots[0].diameter_m, 0.3);
  EXPECT_NEAR(s.slots[1].relative_deg, 90, 1e-9);
  EXPECT_DOUBLE_EQ(s.slots[1].step_m, 0.2);
  EXPECT_NEAR(s.slots[2].relative_deg, 180, 1e-9);
  EXPECT_NEAR(s.slots[3].relative_deg, 270, 1e-9);
  const std::vector<SlotIndex> order = signature_slot_order(map, m0, SlotIndex{2});
  EXPECT_EQ(order,
            (std::vector<SlotIndex>{SlotIndex{2}, SlotIndex{3}, SlotIndex{0}, SlotIndex{1}}));
  EXPECT_TRUE(check_signature(s).has_value());
}

TEST(ManholeSignature, MatchesWithinNoiseAndSaysWhyNot) {
  const SewerMap map = cross();
  const ManholeId m0 = *map.find_manhole("M0");
  const ManholeSignature want = expected_signature(map, m0, SlotIndex{0});
  ManholeSignature seen = want;
  seen.slots[1].relative_deg += 12;
  const SignatureMatch close = compare(want, seen);
  EXPECT_TRUE(close.matches) << close.reason;

  ManholeSignature off = want;
  off.slots[2].relative_deg += 45;
  const SignatureMatch wrong = compare(want, off);
  EXPECT_FALSE(wrong.matches);
  EXPECT_NE(wrong.reason.find("slot 3"), std::string::npos) << wrong.reason;
  EXPECT_LT(wrong.log_likelihood, close.log_likelihood);

  ManholeSignature fewer = want;
  fewer.slots.pop_back();
  const SignatureMatch count = compare(want, fewer);
  EXPECT_FALSE(count.matches);
  EXPECT_EQ(count.reason, "3 slots seen, 4 expected: no slot seen at " +
                              std::to_string(std::lround(want.slots[3].relative_deg)) + "°");
}

// A lateral the map lacks, seen between two mapped mouths: the mouths after it are still paired
// with theirs (not each with the next one along), so the manhole is far likelier than one whose
// mouths all differ, and the reason names the extra mouth.
TEST(ManholeSignature, AnExtraOrMissingMouthIsPairedAroundNotShifted) {
  const ManholeSignature want{.slots = {{0, 0, 0.6}, {135, 0, 0.6}, {225, 0, 0.6}},
                              .shaft_diameter_m = 1.2};
  ManholeSignature extra = want;
  extra.slots.insert(extra.slots.begin() + 1, SlotSighting{27, 0.1, 0.2});
  const SignatureMatch seen = compare(want, extra);
  EXPECT_FALSE(seen.matches);
  EXPECT_EQ(seen.reason, "4 slots seen, 3 expected: slot 2 at 27° is not on the map");
  // One unpaired mouth and the others exact: the penalty and nothing else of note.
  const SignatureMatch same = compare(want, want);
  EXPECT_NEAR(seen.log_likelihood, same.log_likelihood + kSlotCountLogPenalty, 1e-9);

  ManholeSignature missing = want;
  missing.slots.erase(missing.slots.begin() + 1);
  const SignatureMatch gone = compare(want, missing);
  EXPECT_EQ(gone.reason, "2 slots seen, 3 expected: no slot seen at 135°");
  EXPECT_EQ(gone.unseen, std::vector<std::size_t>{1});
  EXPECT_TRUE(gone.unexpected.empty());
  EXPECT_TRUE(seen.unseen.empty());
  EXPECT_EQ(seen.unexpected, std::vector<std::size_t>{1});  // the filter remembers it by this
  // One mouth fewer to score, and the penalty: not the 90-degree misses of a shifted pairing.
  EXPECT_GT(gone.log_likelihood, same.log_likelihood + 2 * kSlotCountLogPenalty);
}

// With the share of manholes that have a mouth the map lacks (SignatureNoise::unmapped_mouth_share,
// as the localisation sets it), a mouth seen and left unpaired costs that share of a mouth nothing
// predicts, not kSlotCountLogPenalty: the scale of a manhole the map lacks, whose mouths beyond
// the pipe's are unknown. A mouth expected and not seen still costs the penalty; whether the
// manhole matches does not change.
TEST(ManholeSignature, AMouthTheMapLacksCostsTheShareOfManholesWithOne) {
  const ManholeSignature want{.slots = {{0, 0, 0.3}, {180, 0, 0.3}}, .shaft_diameter_m = 1.0};
  ManholeSignature extra = want;
  extra.slots.push_back(SlotSighting{255, 0.1, 0.2});
  const SignatureNoise noise{.unmapped_mouth_share = 0.01};
  const SignatureMatch same = compare(want, want, noise);
  const SignatureMatch seen = compare(want, extra, noise);
  EXPECT_FALSE(seen.matches);
  EXPECT_EQ(seen.reason, "3 slots seen, 2 expected: slot 3 at 255° is not on the map");
  EXPECT_EQ(seen.unexpected, std::vector<std::size_t>{2});
  EXPECT_NEAR(unexpected_mouth_log_likelihood(noise),
              std::log(0.01) + unknown_mouth_log_likelihood(), 1e-12);
  EXPECT_NEAR(seen.log_likelihood,
              same.log_likelihood + std::log(0.01) + unknown_mouth_log_likelihood(), 1e-9);
  // About e^-7.7 against e^-12: 70 times likelier than with the flat penalty.
  EXPECT_GT(seen.log_likelihood - compare(want, extra).log_likelihood, 4.0);
  EXPECT_EQ(unexpected_mouth_log_likelihood(SignatureNoise{}), kSlotCountLogPenalty);

  const SignatureMatch gone = compare(extra, want, noise);  // the map's third mouth not seen
  EXPECT_EQ(gone.unseen, std::vector<std::size_t>{2});
  EXPECT_NEAR(gone.log_likelihood, same.log_likelihood + kSlotCountLogPenalty, 1e-9);
}

// Two pipes entering side by side (6 degrees apart on the official ISYBAU sample): with the
// direction noise, or a map direction off, they are seen in the other order counter-clockwise. The
// pairing follows the pipes (told apart by their sizes), with or without a mouth the map lacks;
// in the map's order the right manhole scored two mouths missing and two extra, and the robot
// read its arrival as a false detection.
TEST(ManholeSignature, NeighboursSeenInTheOtherOrderArePairedWithTheirPipes) {
  const ManholeSignature want{.slots = {{0, 0, 0.5}, {92, 0, 0.3}, {180, 0, 0.4}, {186, 0, 0.1}},
                              .shaft_diameter_m = 1.2};
  ManholeSignature swapped = want;
  swapped.slots[2] = {172, 0, 0.1};
  swapped.slots[3] = {174, 0, 0.4};
  const SignatureMatch same = compare(want, want);
  const SignatureMatch seen = compare(want, swapped);
  EXPECT_TRUE(seen.matches) << seen.reason;
  // Only the directions' differences (6 and 14 degrees, at 8 degrees of noise) cost anything.
  const double direction_cost = 0.5 * (6.0 / 8) * (6.0 / 8) + 0.5 * (14.0 / 8) * (14.0 / 8);
  EXPECT_NEAR(seen.log_likelihood, same.log_likelihood - direction_cost, 1e-9);

  ManholeSignature with_lateral = swapped;
  with_lateral.slots.push_back({258, 0.23, 0.2});
  const SignatureMatch extra = compare(want, with_lateral);
  EXPECT_FALSE(extra.matches);
  EXPECT_EQ(extra.reason, "5 slots seen, 4 expected: slot 5 at 258° is not on the map");
  EXPECT_TRUE(extra.unseen.empty());
  EXPECT_EQ(extra.unexpected, std::vector<std::size_t>{4});
  EXPECT_NEAR(extra.log_likelihood, seen.log_likelihood + kSlotCountLogPenalty, 1e-9);
}

TEST(ManholeSignature, ImpossibleObservationsAreErrors) {
  ManholeSignature none;
  none.shaft_diameter_m = 1;
  EXPECT_FALSE(check_signature(none).has_value());
  ManholeSignature bad{.slots = {{0, 0, 0.3}, {400, 0, 0.3}}, .shaft_diameter_m = 1};
  ASSERT_FALSE(check_signature(bad).has_value());
  EXPECT_NE(check_signature(bad).error().message.find("slot 2"), std::string::npos);
  bad.slots[1].relative_deg = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(check_signature(bad).has_value());
  bad.slots[1].relative_deg = 90;
  bad.shaft_diameter_m = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(check_signature(bad).has_value());
}

TEST(MapDiscrepancy, NamesRoundTripAndSameDifferenceIgnoresValues) {
  for (auto kind : {Discrepancy::Kind::kLengthOff, Discrepancy::Kind::kDirectionOff,
                    Discrepancy::Kind::kPositionOff, Discrepancy::Kind::kDiameterSmaller,
                    Discrepancy::Kind::kUnmappedJunction, Discrepancy::Kind::kUnmappedLateral,
                    Discrepancy::Kind::kMissingLateral}) {
    EXPECT_EQ(parse_discrepancy_kind(to_string(kind)), kind);
  }
  EXPECT_FALSE(parse_discrepancy_kind("wrong").has_value());
  const SewerMap map = cross();
  const Discrepancy a{.kind = Discrepancy::Kind::kUnmappedJunction,
                      .pipe = map.find_pipe("P1"),
                      .offset_m = 4,
                      .value = 3};
  Discrepancy b = a;
  b.offset_m = 7;
  b.value = 4;
  EXPECT_TRUE(same_difference(a, b));
  b.offset_m = 12;
  EXPECT_FALSE(same_difference(a, b));
  EXPECT_EQ(describe(a, map), "P1: a manhole the map lacks at 4.00 m, with 3 slots");
}

}  // namespace
}  // namespace sewerplan
