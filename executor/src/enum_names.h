// SPDX-License-Identifier: MIT
// An enum's names: one constexpr table of {value, name} pairs per enum, read both ways, so that a
// value's name is written once and writing and parsing cannot drift apart.
//
// Private to executor:
//
//   constexpr std::array<std::pair<Colour, std::string_view>, 2> kColours{{
//       {Colour::kRed, "red"},
//       {Colour::kBlue, "blue"},
//   }};
//   static_assert(detail::distinct(kColours));
//   std::string_view to_string(Colour c) { return detail::name_of(kColours, c); }
//   std::optional<Colour> parse_colour(std::string_view s) { return detail::value_of(kColours, s);
//   }
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>

namespace sewerplan::executor::detail {

template <class Enum, std::size_t N>
using EnumNames = std::array<std::pair<Enum, std::string_view>, N>;

// No value and no name twice (checked at compile time with static_assert).
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
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return names.front().second;
}

// The value named `name`, empty for any other text.
template <class Enum, std::size_t N>
constexpr std::optional<Enum> value_of(const EnumNames<Enum, N>& names, std::string_view name) {
  for (const auto& [v, n] : names) {
    if (n == name) return v;
  }
  return std::nullopt;
}

}  // namespace sewerplan::executor::detail
