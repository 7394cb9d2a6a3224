// SPDX-License-Identifier: MIT
// An enum's names: one constexpr table of {value, name} pairs per enum, read both ways, so that a
// value's name is written once and writing and parsing cannot drift apart.
//
// The names are what files, logs and command lines carry ("blind-end", "length-off", "risk_aware"):
// an enum's to_string and its parser (parse_*, *_from_string) both read its table, never a switch
// beside a second list. The CAN codes of hal/can/wire_codes.h follow the same rule for bytes. The
// table lives in the .cc file beside the two functions; distinct() checks it at compile time, and a
// round-trip test of each enum (every value to its name and back) catches a value left out, which
// no compiler warns of for a table as it does for a switch.
//
//   constexpr detail::EnumNames<Colour, 2> kColours{{
//       {Colour::kRed, "red"},
//       {Colour::kBlue, "blue"},
//   }};
//   static_assert(detail::distinct(kColours));
//   std::string_view to_string(Colour c) { return detail::name_of(kColours, c); }
//   std::optional<Colour> parse_colour(std::string_view s) { return detail::value_of(kColours, s);
//   }
//   std::string colour_names() { return detail::names_joined(kColours); }  // "red, blue"
//
// A message or help text that lists what a parser accepts takes the list from the table too
// (names_joined, through a *_names() function beside the parser), never a literal of its own.
//
// Inside a library with a detail namespace of its own (domain, search, executor), that namespace
// hides this one: write sewerplan::detail::name_of there.
//
// Runtime: O(N) per lookup, for tables of a few to a few dozen names.
// Thread safety: constants and pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace sewerplan::detail {

template <class Enum, std::size_t N>
using EnumNames = std::array<std::pair<Enum, std::string_view>, N>;

// No value and no name twice, and no empty name (checked at compile time with static_assert).
template <class Enum, std::size_t N>
constexpr bool distinct(const EnumNames<Enum, N>& names) {
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i].second.empty()) return false;
    for (std::size_t j = i + 1; j < N; ++j) {
      if (names[i].first == names[j].first || names[i].second == names[j].second) return false;
    }
  }
  return true;
}

// The name of `value`; the table's first name for a value it lacks (none, once the round-trip test
// of the enum passes).
template <class Enum, std::size_t N>
constexpr std::string_view name_of(const EnumNames<Enum, N>& names, Enum value) {
  static_assert(N > 0);
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return names.front().second;
}

// The value named `name` (exactly: case and spelling), empty for any other text.
template <class Enum, std::size_t N>
constexpr std::optional<Enum> value_of(const EnumNames<Enum, N>& names, std::string_view name) {
  for (const auto& [v, n] : names) {
    if (n == name) return v;
  }
  return std::nullopt;
}

// Every name of the table in its order, separated by ", ": "red, green, blue".
template <class Enum, std::size_t N>
std::string names_joined(const EnumNames<Enum, N>& names) {
  std::string out;
  for (const auto& [v, name] : names) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

}  // namespace sewerplan::detail
