// SPDX-License-Identifier: MIT
#include "plan_lexer.h"

#include <charconv>

#include "object_names.h"

namespace sewerplan::domain::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Drops FF's "step 0:" or "1:" in front of an action, if there is one.
std::string_view strip_step_number(std::string_view line) {
  std::string_view s = line;
  if (s.size() > 4 && equals_ignoring_case(s.substr(0, 4), "step") &&
      (is_space(s[4]) || is_digit(s[4]))) {
    s = trim(s.substr(4));
  }
  std::size_t digits = 0;
  while (digits < s.size() && is_digit(s[digits])) ++digits;
  if (digits == 0) return line;
  s = trim(s.substr(digits));
  if (s.empty() || s.front() != ':') return line;
  return trim(s.substr(1));
}

// Reads a decimal number at the front of `s` and drops it; empty if there is none or it is huge.
std::optional<std::uint32_t> take_number(std::string_view& s) {
  std::size_t digits = 0;
  while (digits < s.size() && is_digit(s[digits])) ++digits;
  if (digits == 0 || digits > 6) return std::nullopt;
  std::uint32_t value = 0;
  std::from_chars(s.data(), s.data() + digits, value);
  s.remove_prefix(digits);
  return value;
}

bool take_prefix(std::string_view& s, std::string_view prefix) {
  if (s.substr(0, prefix.size()) != prefix) return false;
  s.remove_prefix(prefix.size());
  return true;
}

}  // namespace

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string quote_token(std::string_view token) {
  constexpr std::size_t kMax = 60;
  constexpr char kHex[] = "0123456789abcdef";
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

std::variant<std::string_view, std::string> action_text(std::string_view line) {
  if (const std::size_t comment = line.find(';'); comment != std::string_view::npos) {
    line = line.substr(0, comment);
  }
  line = trim(line);
  if (line.empty() || line.front() == '#') return std::string_view{};
  line = strip_step_number(line);
  if (!line.empty() && line.front() == '(') {
    if (line.back() != ')') return std::string("a '(' without its ')'");
    line = trim(line.substr(1, line.size() - 2));
    if (line.empty()) return std::string("an empty action '()'");
  }
  return line;
}

std::vector<std::string_view> split(std::string_view s) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > start) tokens.push_back(s.substr(start, i - start));
  }
  return tokens;
}

std::optional<DriveManholeName> read_drive_manhole_name(std::string_view upper_name) {
  std::string_view s = upper_name;
  DriveManholeName n;
  if (!take_prefix(s, kDriveManholePrefix)) return std::nullopt;
  auto type = take_number(s);
  if (!type) return std::nullopt;
  n.type = *type;
  if (take_prefix(s, "_TYPE_")) {
    if (s.empty() || s.front() < 'A' || s.front() > 'Z') return std::nullopt;
    n.variant = s.front();
    s.remove_prefix(1);
  }
  if (!take_prefix(s, "_FROM_")) return std::nullopt;
  auto from = take_number(s);
  if (!from || !take_prefix(s, "_TO_")) return std::nullopt;
  auto to = take_number(s);
  if (!to || !s.empty()) return std::nullopt;
  n.from = *from;
  n.to = *to;
  return n;
}

NameIndex::NameIndex(std::string kind, Exact exact, All all)
    : kind_(std::move(kind)), exact_(std::move(exact)), all_(std::move(all)) {}

std::variant<std::uint32_t, std::string> NameIndex::find(std::string_view token) {
  if (auto id = exact_(token)) return *id;
  if (!folded_) {
    folded_.emplace();
    names_ = all_();
    for (std::size_t i = 0; i < names_.size(); ++i) {
      (*folded_)[ascii_upper(names_[i])].push_back(static_cast<std::uint32_t>(i));
    }
  }
  auto it = folded_->find(ascii_upper(token));
  if (it == folded_->end()) return "unknown " + kind_ + " " + quote_token(token);
  if (it->second.size() == 1) return it->second.front();
  std::string message = quote_token(token) + " names several " + kind_ + "s ignoring case:";
  for (std::uint32_t i : it->second) message += " " + names_[i];
  return message;
}

}  // namespace sewerplan::domain::detail
