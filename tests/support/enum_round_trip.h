// SPDX-License-Identifier: MIT
// The round-trip test of an enum's names (sewerplan/core/enum_names.h): every value listed has a
// name of its own, and its name parses back to it; other text parses to nothing. The values are
// listed by the test, not taken from the table, so a value left out of its table fails here.
//
//   expect_round_trip({BeaconState::kNone, BeaconState::kConfirmed, ...}, parse_beacon_state);
#pragma once

#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

namespace sewerplan::testing {

// `to_string(value)` is found by argument-dependent lookup, beside the enum.
template <class Enum, class Parse>
void expect_round_trip(std::initializer_list<Enum> values, Parse parse) {
  std::set<std::string_view> names;
  for (Enum value : values) {
    const std::string_view name = to_string(value);
    SCOPED_TRACE(std::string(name));
    EXPECT_FALSE(name.empty());
    EXPECT_TRUE(names.insert(name).second) << "two values named '" << name << "'";
    const std::optional<Enum> back = parse(name);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, value);
    EXPECT_FALSE(parse(std::string(name) + " ").has_value()) << "a name is read exactly";
  }
  EXPECT_FALSE(parse("").has_value());
  EXPECT_FALSE(parse("no such name").has_value());
}

}  // namespace sewerplan::testing
