// SPDX-License-Identifier: MIT
#include "sewerplan/core/crs.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace sewerplan {

std::string Crs::to_string() const { return authority + ":" + std::to_string(code); }

namespace {

bool starts_with_ignoring_case(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() &&
         std::equal(prefix.begin(), prefix.end(), text.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

}  // namespace

Result<Crs> parse_crs(std::string_view text) {
  const auto invalid = [&](std::string_view why) {
    return Error{ErrorCode::kInvalidArgument, "CRS \"" + std::string(text) +
                                                  "\": " + std::string(why) +
                                                  " (expected AUTHORITY:CODE, e.g. EPSG:25832)"};
  };
  std::string_view rest = text;
  constexpr std::string_view kUrn = "urn:ogc:def:crs:";
  const bool urn = starts_with_ignoring_case(rest, kUrn);
  if (urn) rest.remove_prefix(kUrn.size());
  const std::size_t colon = rest.find(':');
  if (colon == std::string_view::npos) return invalid("no ':' between authority and code");
  std::string_view authority = rest.substr(0, colon);
  std::string_view code = rest.substr(colon + 1);
  // The URN has an empty version between authority and code: EPSG::25832.
  if (urn && !code.empty() && code.front() == ':') code.remove_prefix(1);
  if (authority.empty() || !std::all_of(authority.begin(), authority.end(), [](char c) {
        return std::isalpha(static_cast<unsigned char>(c)) != 0;
      })) {
    return invalid("the authority must be letters");
  }
  std::uint32_t number = 0;
  const auto [end, ec] = std::from_chars(code.data(), code.data() + code.size(), number);
  if (code.empty() || ec != std::errc() || end != code.data() + code.size() || number == 0 ||
      !std::isdigit(static_cast<unsigned char>(code.front()))) {
    return invalid("the code must be a positive number");
  }
  Crs crs{.authority = std::string(authority), .code = number};
  std::transform(crs.authority.begin(), crs.authority.end(), crs.authority.begin(), [](char c) {
    return static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  });
  return crs;
}

}  // namespace sewerplan
