// SPDX-License-Identifier: MIT
// JsonScan: a forward-only reader of JSON tokens straight from the text, with no document tree.
//
// Private to core. The map reader's fast path (map_json.cc) reads a well-formed map with it in one
// pass, holding nothing but the text and the records it builds: a 1,000,000-manhole map (430 MB)
// in a simdjson document tree took 2.3 GB and 9 s (bench/core/map_load_bench.cc). It accepts only
// what it can read exactly as simdjson would: any token it does not know (a string with an escape,
// an integer of more than 18 digits, "-0", a number out of double's range) or any syntax error
// makes it fail, and the caller then reads the text with the document reader, which reports every
// problem with its place. So failing is always safe; accepting must never differ from simdjson.
//
//   JsonScan scan(text);
//   std::string_view key;
//   double v = 0;
//   bool ok = scan.consume('{') && scan.string(key) && scan.consume(':') && scan.number(v);
//
// Thread safety: one JsonScan per thread.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "sewerplan/core/text_file.h"

namespace sewerplan::detail {

class JsonScan {
 public:
  explicit JsonScan(std::string_view text) : text_(text) {}

  // Skips white space, then takes `c` if it is next.
  bool consume(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  // Where the scan is in the text, and the text's size (bytes).
  std::size_t position() const { return pos_; }
  std::size_t size() const { return text_.size(); }

  // Only white space is left.
  bool at_end() {
    skip_space();
    return pos_ == text_.size();
  }

  // A string without escapes, of valid UTF-8 and no control characters: a view into the text.
  bool string(std::string_view& out) {
    if (!consume('"')) return false;
    const std::size_t begin = pos_;
    bool ascii = true;
    while (pos_ < text_.size()) {
      const auto c = static_cast<unsigned char>(text_[pos_]);
      if (c == '"') {
        out = text_.substr(begin, pos_ - begin);
        ++pos_;
        return ascii || is_valid_utf8(out);
      }
      if (c == '\\' || c < 0x20) return false;
      ascii = ascii && c < 0x80;
      ++pos_;
    }
    return false;
  }

  // A number in JSON's grammar, converted as simdjson converts it (integers through int64,
  // others correctly rounded: std::from_chars).
  bool number(double& out) {
    skip_space();
    const std::size_t begin = pos_;
    if (pos_ < text_.size() && text_[pos_] == '-') ++pos_;
    const std::size_t int_begin = pos_;
    if (pos_ >= text_.size() || !is_digit(text_[pos_])) return false;
    if (text_[pos_] == '0') {
      ++pos_;
    } else {
      while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
    }
    const std::size_t int_digits = pos_ - int_begin;
    bool integer = true;
    if (pos_ < text_.size() && text_[pos_] == '.') {
      integer = false;
      ++pos_;
      if (!digits()) return false;
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      integer = false;
      ++pos_;
      if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
      if (!digits()) return false;
    }
    const char* first = text_.data() + begin;
    const char* last = text_.data() + pos_;
    if (integer) {
      if (int_digits > 18 || (last - first == 2 && first[0] == '-' && first[1] == '0')) {
        return false;
      }
      std::int64_t i = 0;
      if (std::from_chars(first, last, i).ptr != last) return false;
      out = static_cast<double>(i);
      return true;
    }
    const auto [end, ec] = std::from_chars(first, last, out);
    return ec == std::errc{} && end == last;
  }

  bool boolean(bool& out) {
    skip_space();
    if (literal("true")) {
      out = true;
      return true;
    }
    if (literal("false")) {
      out = false;
      return true;
    }
    return false;
  }

  bool null() {
    skip_space();
    return literal("null");
  }

  // The next token starts with `c` (after white space); nothing is taken.
  bool peek(char c) {
    skip_space();
    return pos_ < text_.size() && text_[pos_] == c;
  }

  // An object: `field(key)` reads each member's value; false as soon as anything fails.
  template <class Field>
  bool object(Field&& field) {
    if (!consume('{')) return false;
    if (consume('}')) return true;
    do {
      std::string_view key;
      if (!string(key) || !consume(':') || !field(key)) return false;
    } while (consume(','));
    return consume('}');
  }

  // An array: `element()` reads each element.
  template <class Element>
  bool array(Element&& element) {
    if (!consume('[')) return false;
    if (consume(']')) return true;
    do {
      if (!element()) return false;
    } while (consume(','));
    return consume(']');
  }

 private:
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }

  bool digits() {
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
    return pos_ > begin;
  }

  bool literal(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    // simdjson wants a structural character or white space after an atom.
    if (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c != ',' && c != '}' && c != ']' && c != ' ' && c != '\t' && c != '\n' && c != '\r') {
        return false;
      }
    }
    return true;
  }

  void skip_space() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c != ' ' && c != '\n' && c != '\r' && c != '\t') return;
      ++pos_;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

}  // namespace sewerplan::detail
