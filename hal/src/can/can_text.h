// SPDX-License-Identifier: MIT
// Hex and printable text for the CAN code's frames and error messages (hal/src/can only).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sewerplan::hal {

// `value` in upper-case hex, zero-padded to at least `digits`.
inline std::string hex_text(std::uint32_t value, int digits) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string text;
  do {
    text.insert(text.begin(), kDigits[value & 0xfU]);
    value >>= 4U;
  } while (value != 0);
  while (static_cast<int>(text.size()) < digits) text.insert(text.begin(), '0');
  return text;
}

// Hex digits (either case) to a number; empty if a character is not a hex digit or it is too long.
inline std::optional<std::uint32_t> parse_hex(std::string_view text) {
  if (text.empty() || text.size() > 8) return std::nullopt;
  std::uint32_t value = 0;
  for (char c : text) {
    std::uint32_t digit = 0;
    if (c >= '0' && c <= '9') {
      digit = static_cast<std::uint32_t>(c - '0');
    } else if (c >= 'a' && c <= 'f') {
      digit = static_cast<std::uint32_t>(c - 'a' + 10);
    } else if (c >= 'A' && c <= 'F') {
      digit = static_cast<std::uint32_t>(c - 'A' + 10);
    } else {
      return std::nullopt;
    }
    value = (value << 4U) | digit;
  }
  return value;
}

// Bytes for an error message: printable ASCII as is, others as \xNN; at most 40 characters.
inline std::string printable(std::string_view bytes) {
  std::string text;
  for (char c : bytes.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      text += c;
    } else {
      text += "\\x" + hex_text(u, 2);
    }
  }
  if (bytes.size() > 40) text += "...";
  return text;
}

}  // namespace sewerplan::hal
