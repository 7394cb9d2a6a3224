// SPDX-License-Identifier: MIT
// An enum's names (enum_names.h): the table's checks and lookups, and every name table of core read
// both ways.
#include "sewerplan/core/enum_names.h"

#include <string_view>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_discrepancy.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/sewer_map.h"

#include "risk_effect_names.h"
#include "support/enum_round_trip.h"

namespace sewerplan {
namespace {

using testing::expect_round_trip;

enum class Colour { kRed, kGreen, kBlue };

constexpr detail::EnumNames<Colour, 3> kColours{{
    {Colour::kRed, "red"},
    {Colour::kGreen, "green"},
    {Colour::kBlue, "blue"},
}};

TEST(EnumNames, ATableIsDistinctOnlyWithoutAValueOrANameTwiceAndWithoutAnEmptyName) {
  static_assert(detail::distinct(kColours));
  constexpr detail::EnumNames<Colour, 2> value_twice{{{Colour::kRed, "red"}, {Colour::kRed, "r"}}};
  constexpr detail::EnumNames<Colour, 2> name_twice{
      {{Colour::kRed, "red"}, {Colour::kBlue, "red"}}};
  constexpr detail::EnumNames<Colour, 1> empty_name{{{Colour::kRed, ""}}};
  EXPECT_FALSE(detail::distinct(value_twice));
  EXPECT_FALSE(detail::distinct(name_twice));
  EXPECT_FALSE(detail::distinct(empty_name));
}

TEST(EnumNames, ReadsANameAndAValueBothWays) {
  static_assert(detail::name_of(kColours, Colour::kGreen) == "green");
  static_assert(detail::value_of(kColours, "blue") == Colour::kBlue);
  EXPECT_EQ(detail::name_of(kColours, Colour::kBlue), "blue");
  EXPECT_EQ(detail::value_of(kColours, "red"), Colour::kRed);
  EXPECT_FALSE(detail::value_of(kColours, "Red").has_value()) << "names are read exactly";
  EXPECT_FALSE(detail::value_of(kColours, "").has_value());
}

TEST(EnumNames, JoinsEveryNameInTheTablesOrder) {
  EXPECT_EQ(detail::names_joined(kColours), "red, green, blue");
}

TEST(EnumNames, AValueTheTableLacksGetsItsFirstName) {
  constexpr detail::EnumNames<Colour, 2> partial{{{Colour::kRed, "red"}, {Colour::kBlue, "blue"}}};
  EXPECT_EQ(detail::name_of(partial, Colour::kGreen), "red");
}

TEST(EnumNames, EveryValueOfCoreRoundTripsThroughItsNameAndBack) {
  using Kind = Discrepancy::Kind;
  expect_round_trip(
      {Kind::kLengthOff, Kind::kDirectionOff, Kind::kPositionOff, Kind::kDiameterSmaller,
       Kind::kUnmappedJunction, Kind::kUnmappedLateral, Kind::kMissingLateral},
      parse_discrepancy_kind);
  expect_round_trip(
      {PipeShape::kCircular, PipeShape::kRectangular, PipeShape::kEgg, PipeShape::kOther},
      pipe_shape_from_string);
  expect_round_trip({MapFormat::kJson, MapFormat::kAscii, MapFormat::kSwmm, MapFormat::kIsybau},
                    map_format_from_name);
  expect_round_trip({Topology::kTree, Topology::kMeshed}, topology_from_string);
  // Read by the risk table's reader through the table, private to core.
  expect_round_trip(
      {RiskEffect::kNone, RiskEffect::kDanger, RiskEffect::kBlockage, RiskEffect::kImpassable},
      [](std::string_view name) { return detail::value_of(detail::kRiskEffectNames, name); });
}

}  // namespace
}  // namespace sewerplan
