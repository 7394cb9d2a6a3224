// SPDX-License-Identifier: MIT
// The lexical layer of the ASCII sewer database (map_ascii.h), shared by its reader and writer:
// lines, tokens, numbers and which names can stand as one token. Private to core/src.
//
// A line is split at '\n' (a '\r' before it is dropped); its tokens are separated by spaces and
// tabs, and a token starting with '#' starts a comment that runs to the end of the line. Numbers
// are read with std::from_chars and written with std::to_chars in the shortest form that reads
// back to the same value, so a map survives a write and a read exactly.
//
//   LineReader lines(text);
//   std::vector<std::string_view> tokens;
//   for (std::string_view line; lines.next(line);) {
//     tokenize(line, tokens);
//     ...
//   }
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sewerplan::ascii_syntax {

inline constexpr std::string_view kHeaderKeyword = "sewerdb";
inline constexpr std::string_view kFormatVersion = "1";
// The value of a pipe's `from` or `to` for a blind end; hence no manhole may be called so.
inline constexpr std::string_view kBlindEnd = "-";

// The lines of a text, in order, numbered from 1.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  // The next line without its '\n' (and without a '\r' before it); false after the last line.
  bool next(std::string_view& line);
  // The number of the line last returned by next(), from 1 (saturates at the largest uint32).
  std::uint32_t line_number() const { return line_number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::uint32_t line_number_ = 0;
};

// Replaces `tokens` with the tokens of `line`, up to a comment. Tokens are views into `line`.
void tokenize(std::string_view line, std::vector<std::string_view>& tokens);

enum class NumberError { kNone, kNotANumber, kNotFinite, kOutOfRange };

// Reads all of `text` as a decimal number ("-1.5", "2e-3"); no leading '+', no trailing
// characters, no white space. nan and inf are kNotFinite.
NumberError parse_number(std::string_view text, double& value);
NumberError parse_number(std::string_view text, float& value);

// Appends the shortest text that parse_number reads back as exactly `value`.
void append_number(std::string& out, double value);
void append_number(std::string& out, float value);

// Why `name` cannot be written as one name token (a map, manhole, pipe or point name), or empty if
// it can: it must be non-empty, without white space or control characters, not start with '#'
// (a comment) and not contain '=' (a key).
std::string_view name_problem(std::string_view name);

// `text` in single quotes, shortened to its first few dozen characters if long (the text may be
// arbitrary input: control characters escaped, message_text.h's input_quoted).
std::string quoted(std::string_view text);

}  // namespace sewerplan::ascii_syntax
