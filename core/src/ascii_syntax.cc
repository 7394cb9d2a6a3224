// SPDX-License-Identifier: MIT
#include "ascii_syntax.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

#include "sewerplan/core/message_text.h"

namespace sewerplan::ascii_syntax {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

template <class T>
NumberError parse_floating(std::string_view text, T& value) {
  const char* const first = text.data();
  const char* const last = text.data() + text.size();
  T parsed{};
  const std::from_chars_result result = std::from_chars(first, last, parsed);
  if (result.ec == std::errc::result_out_of_range) return NumberError::kOutOfRange;
  if (result.ec != std::errc() || result.ptr != last) return NumberError::kNotANumber;
  if (!std::isfinite(parsed)) return NumberError::kNotFinite;
  value = parsed;
  return NumberError::kNone;
}

template <class T>
void append_floating(std::string& out, T value) {
  // The shortest round-trip form of a double has at most 24 characters
  // ("-2.2250738585072014e-308").
  std::array<char, 64> buffer{};
  const std::to_chars_result result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.append(buffer.data(), result.ptr);
}

}  // namespace

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
  line = text_.substr(pos_, end - pos_);
  pos_ = end + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (line_number_ < std::numeric_limits<std::uint32_t>::max()) ++line_number_;
  return true;
}

void tokenize(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    if (is_blank(line[i])) {
      ++i;
      continue;
    }
    if (line[i] == '#') break;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    tokens.push_back(line.substr(start, i - start));
  }
}

NumberError parse_number(std::string_view text, double& value) {
  return parse_floating(text, value);
}

NumberError parse_number(std::string_view text, float& value) {
  return parse_floating(text, value);
}

void append_number(std::string& out, double value) { append_floating(out, value); }
void append_number(std::string& out, float value) { append_floating(out, value); }

std::string_view name_problem(std::string_view name) {
  if (name.empty()) return "it is empty";
  if (name.front() == '#') return "it starts with '#', which would start a comment";
  for (char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 0x20 || u == 0x7f) return "it contains white space or a control character";
    if (c == '=') return "it contains '=', which would make it a key";
  }
  return {};
}

std::string quoted(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  return input_quoted(text, kMaxShown);
}

}  // namespace sewerplan::ascii_syntax
