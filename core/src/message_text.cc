// SPDX-License-Identifier: MIT
#include "sewerplan/core/message_text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace sewerplan {
namespace {

void append_byte_escape(std::string& out, unsigned char c) {
  std::array<char, 8> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "\\x%02X", c);
  out.append(buffer.data());
}

// The length of the valid UTF-8 sequence at text[i], or 0 if there is none.
std::size_t utf8_length(std::string_view text, std::size_t i, std::uint32_t& code) {
  const auto b0 = static_cast<unsigned char>(text[i]);
  std::size_t n = 0;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    n = 2;
    code = b0 & 0x1FU;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    n = 3;
    code = b0 & 0x0FU;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    n = 4;
    code = b0 & 0x07U;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(text[i + k]);
    if ((b & 0xC0U) != 0x80U) return 0;
    code = (code << 6U) | (b & 0x3FU);
  }
  const bool overlong = (n == 3 && code < 0x800) || (n == 4 && code < 0x10000);
  const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
  if (overlong || surrogate || code > 0x10FFFF) return 0;
  return n;
}

}  // namespace

std::string input_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      if (c < 0x20 || c == 0x7F) {
        append_byte_escape(out, c);
      } else {
        out.push_back(static_cast<char>(c));
      }
      ++i;
      continue;
    }
    std::uint32_t code = 0;
    const std::size_t n = utf8_length(text, i, code);
    if (n == 0) {
      append_byte_escape(out, c);
      ++i;
    } else if (code >= 0x80 && code <= 0x9F) {  // the C1 controls
      std::array<char, 8> buffer{};
      std::snprintf(buffer.data(), buffer.size(), "\\u%04X", static_cast<unsigned>(code));
      out.append(buffer.data());
      i += n;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

std::string input_quoted(std::string_view text, std::size_t max_bytes) {
  const bool cut = text.size() > max_bytes;
  return "'" + input_text(cut ? text.substr(0, max_bytes) : text) + (cut ? "...'" : "'");
}

std::string number_text(double v, int digits) {
  std::array<char, 400> buffer{};
  char* const first = buffer.data();
  char* const last = first + buffer.size();
  const double magnitude = std::abs(v);
  if (!std::isfinite(v) || (magnitude != 0 && (magnitude < 1e-4 || magnitude >= 1e15))) {
    return {first, std::to_chars(first, last, v, std::chars_format::general, digits).ptr};
  }
  // Plain decimals: `digits` significant ones, or the whole integer part if it is longer.
  const int exponent = magnitude == 0 ? 0 : static_cast<int>(std::floor(std::log10(magnitude)));
  const int decimals = std::max(0, digits - 1 - exponent);
  std::string text(first, std::to_chars(first, last, v, std::chars_format::fixed, decimals).ptr);
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

LimitText limit_text(double value, double limit, int min_digits) {
  constexpr int kMaxDigits = 17;  // round-trips any double
  int digits = min_digits;
  LimitText t{number_text(value, digits), number_text(limit, digits)};
  while (value != limit && t.value == t.limit && digits < kMaxDigits) {
    ++digits;
    t = {number_text(value, digits), number_text(limit, digits)};
  }
  return t;
}

LimitText limit_text_fixed(double value, double limit, int decimals) {
  constexpr int kMaxDecimals = 17;
  auto fixed = [](double v, int d) {
    std::array<char, 400> buffer{};
    char* const first = buffer.data();
    return std::string(
        first, std::to_chars(first, first + buffer.size(), v, std::chars_format::fixed, d).ptr);
  };
  LimitText t{fixed(value, decimals), fixed(limit, decimals)};
  while (value != limit && t.value == t.limit && decimals < kMaxDecimals) {
    ++decimals;
    t = {fixed(value, decimals), fixed(limit, decimals)};
  }
  return t;
}

}  // namespace sewerplan
