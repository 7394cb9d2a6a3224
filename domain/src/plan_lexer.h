// SPDX-License-Identifier: MIT
// Internal to parse_plan (plan_parse.cc): the lexical side of reading a plan's line, and name
// look-up that falls back to ignoring case. Everything here accepts any bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <variant>
#include <vector>

namespace sewerplan::domain::detail {

inline constexpr std::string_view kDriveManholePrefix = "DRIVE_MANHOLE_TYPE_";
inline constexpr std::string_view kActionNames =
    "DRIVE_PIPE_TO_MANHOLE, DRIVE_MANHOLE_TYPE_k[_TYPE_V]_FROM_i_TO_j, ENTER_PIPE, "
    "TAKE_WATER_SAMPLE, INSPECT_PIPE, GO_TO_POINT, GO_TO_MANHOLE";

std::string_view trim(std::string_view s);

// A token as a message may show it: quoted, bytes other than printable ASCII escaped (\xNN), and
// cut short when long.
std::string quote_token(std::string_view token);

// The action part of a line: without a ';' comment, FF's "step 0:" or "1:", and Fast Downward's
// parentheses. Empty for a blank or comment line; an error message for a '(' without ')'.
std::variant<std::string_view, std::string> action_text(std::string_view line);

// White-space separated tokens.
std::vector<std::string_view> split(std::string_view s);

// DRIVE_MANHOLE_TYPE_k[_TYPE_V]_FROM_i_TO_j taken apart; numbers as written (slots from 1).
struct DriveManholeName {
  std::uint32_t type = 0;
  std::optional<char> variant;
  std::uint32_t from = 0;
  std::uint32_t to = 0;
};

// Reads an action name already in upper case; empty if it does not follow the pattern.
std::optional<DriveManholeName> read_drive_manhole_name(std::string_view upper_name);

// Names of one kind of object: exact look-up first, then, through an index built on first need,
// ignoring case when that names exactly one object.
class NameIndex {
 public:
  using Exact = std::function<std::optional<std::uint32_t>(std::string_view)>;
  using All = std::function<std::vector<std::string>()>;
  NameIndex(std::string kind, Exact exact, All all);

  // The object's index, or a message saying why there is none ("unknown pipe 'P99'").
  std::variant<std::uint32_t, std::string> find(std::string_view token);

 private:
  std::string kind_;
  Exact exact_;
  All all_;
  std::vector<std::string> names_;
  std::optional<std::unordered_map<std::string, std::vector<std::uint32_t>>> folded_;
};

}  // namespace sewerplan::domain::detail
